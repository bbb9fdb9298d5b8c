"""Mitsuba 3 side of skinbake: the volumetric ground truth of a layer stack (flat
slab measurements, nested shells under a mesh) and the baked table as a spectral
BSDF. Import skinbake_mitsuba.variant and call choose() before anything that
imports mitsuba."""

import json as _json
import math as _math


def json_finite(o):
    """O with every non-finite float as None: the project's JSON policy (docs/json.md: JSON has
    no NaN or infinity, a number that is not finite is written as null), for json.dump(...,
    allow_nan=False)."""
    if isinstance(o, float) and not _math.isfinite(o):
        return None
    if isinstance(o, dict):
        return {k: json_finite(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [json_finite(v) for v in o]
    return o


def json_dump(o, f, **kw):
    """json.dump of O under the policy (non-finite numbers as null, never NaN or Infinity)."""
    _json.dump(json_finite(o), f, allow_nan=False, **kw)


def _refuse_constant(name):
    raise ValueError(f"{name} is not JSON (docs/json.md: a number that is not finite is null)")


def json_load(f):
    """json.load of F, refusing NaN and Infinity as a strict JSON parser would."""
    return _json.load(f, parse_constant=_refuse_constant)


def json_loads(s):
    """json.loads of S under the same rule as json_load."""
    return _json.loads(s, parse_constant=_refuse_constant)
