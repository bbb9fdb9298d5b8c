"""Calibration constants of the general mode, measured per Blender version and stored with the
version they were measured on.  A version without a measurement gets factor 1 (no correction)."""
import bpy

# Diffuse albedo that Cycles renders per unit Principled Base Color with RANDOM_WALK subsurface,
# under uniform white light, view along the normal, roughness 0: "k0" at "albedo"; it rises by
# "k_per_roughness" per unit roughness (the Principled diffuse retro-reflection term).
MEASURED = {
    (3, 4): {
        "measured_with": "Blender 3.4.1 (Debian 12), Cycles CPU, 64 px, 128-256 spp, +-0.3 %",
        "albedo": (0.05, 0.15, 0.3, 0.6, 0.8),
        "k0": (0.995, 0.991, 0.983, 0.981, 0.987),   # the random-walk albedo inversion runs 0.5-2 % low
        "k_per_roughness": 0.0607,
    },
}


def _interp(xs, ys, x):
    if x <= xs[0]:
        return ys[0]
    if x >= xs[-1]:
        return ys[-1]
    i = max(j for j in range(len(xs) - 1) if xs[j] <= x)
    return ys[i] + (ys[i + 1] - ys[i]) * (x - xs[i]) / (xs[i + 1] - xs[i])


def measurement(version=None):
    """The constants for VERSION (default: this Blender): the 3.4 measurement serves every 3.x;
    None where nothing was measured."""
    v = tuple((version or bpy.app.version)[:2])
    if v in MEASURED:
        return MEASURED[v]
    if v[0] == 3:
        return MEASURED[(3, 4)]
    return None


def albedo_factor(albedo, roughness):
    """Rendered / requested diffuse albedo, per channel: k0(albedo) + k_per_roughness * roughness.
    It rises further toward grazing views (+2 % at 60 deg in 3.4)."""
    c = measurement()
    if c is None:
        return [1.0] * len(albedo)
    r = min(max(roughness, 0.0), 1.0)
    return [_interp(c["albedo"], c["k0"], a) + c["k_per_roughness"] * r for a in albedo]


def sss_albedo_factor(albedo):
    """Rendered / requested albedo of the Principled random-walk subsurface closure (roughness 0)
    under a sun: k0 is its white-furnace value, which includes the exit's Disney light falloff,
    whose cosine-weighted mean is 1 - 1/42."""
    c = measurement()
    if c is None:
        return 1.0
    return _interp(c["albedo"], [k / (1.0 - 1.0 / 42.0) for k in c["k0"]], albedo)
