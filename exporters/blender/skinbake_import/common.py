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
    def refuse(token):
        raise ValueError(f"{token} is not JSON (docs/json.md)")
    return json.load(f, parse_constant=refuse)


class SkinbakeError(Exception):
    """Bad input: an image set, an object name, a mesh without UVs, a scene EEVEE cannot do."""


class ImageSetError(SkinbakeError):
    """The image set is missing, incomplete, corrupt or of an unknown version."""


def say(msg):
    print(f"import_skin.py: {msg}")
