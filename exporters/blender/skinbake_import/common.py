"""What every module of the importer shares: its errors, its messages and the names it gives
to what it adds to a scene (all starting with PREFIX)."""
import json

PREFIX = "skinbake"             # names of everything the importer adds to a scene start with it
UV_SIZE_PROP = PREFIX + "_uv_size"     # object property: metres per UV unit (Attribute, type Object)
VL_EXACT = PREFIX + "_exact"            # view-layer properties the exact material reads
VL_DIR = PREFIX + "_light_dir"          # unit vector toward a sun (0 for point and spot lamps)
VL_POS = PREFIX + "_light_pos"          # lamp position (point and spot)
VL_POINT = PREFIX + "_light_point"      # 1 for point and spot lamps, 0 for suns


def json_load(f):
    """json.load of F refusing NaN, Infinity and -Infinity (ValueError), which Python's json takes
    but JSON has not: skinbake writes a non-finite number as null (docs/json.md)."""
    text = f.read()
    try:
        return json.loads(text, parse_constant=_refuse_constant)
    except ValueError as e:
        where = _non_finite_field(text)
        if where is None:
            raise
        raise ValueError(f"{where}: {e}") from None


def _refuse_constant(token):
    raise ValueError(f"{token} is not JSON, expected a finite number or null (docs/json.md)")


def _non_finite_field(text):
    """The path of the first non-finite number in TEXT (read leniently), as '"key" is [inf, ...]'
    so that the message names the field and its value; None if there is none or TEXT is no JSON."""
    import math
    try:
        doc = json.loads(text)
    except ValueError:
        return None

    def bad(v):
        if isinstance(v, float):
            return not math.isfinite(v)
        return isinstance(v, list) and any(bad(x) for x in v)

    def walk(v):
        if isinstance(v, dict):
            for k, x in v.items():
                if bad(x):
                    return f'"{k}" is {x!r}'
                r = walk(x)
                if r is not None:
                    return r
        if isinstance(v, list):
            for x in v:
                r = walk(x)
                if r is not None:
                    return r
        return None
    return walk(doc)


class SkinbakeError(Exception):
    """Bad input: an image set, an object name, a mesh without UVs, a scene EEVEE cannot do."""


class ImageSetError(SkinbakeError):
    """The image set is missing, incomplete, corrupt or of an unknown version."""


def say(msg):
    print(f"import_skin.py: {msg}")
