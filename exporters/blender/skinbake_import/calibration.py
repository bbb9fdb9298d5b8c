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
    (4, 3): {            # Debian 13's blender package; the same as 4.5 to 4 digits
        "measured_with": "Blender 4.3.2 (Debian 13), Cycles CPU, 64 px, 256 spp (scripts/blender-calibrate.py)",
        "albedo": (0.05, 0.15, 0.3, 0.6, 0.8, 0.95),
        "k0": (0.7701, 0.7947, 0.8328, 0.907, 0.9628, 0.9444),
        "k_per_roughness": 0.0,       # measured -0.0001
    },
    (4, 5): {            # 4.x rebuilt the Principled BSDF: a Lambert-like exit, no retro-reflection term
        "measured_with": "Blender 4.5.15 LTS (bpy), Cycles CPU, 64 px, 256 spp (scripts/blender-calibrate.py)",
        "albedo": (0.05, 0.15, 0.3, 0.6, 0.8, 0.95),
        "k0": (0.7701, 0.7947, 0.8328, 0.907, 0.9628, 0.9444),
        "k_per_roughness": 0.0,       # measured -0.0001
    },
    (5, 0): {
        "measured_with": "Blender 5.0.1 (bpy), Cycles CPU, 64 px, 256 spp (scripts/blender-calibrate.py)",
        "albedo": (0.05, 0.15, 0.3, 0.6, 0.8, 0.95),
        "k0": (0.7692, 0.7954, 0.8323, 0.9083, 0.9627, 0.9447),
        "k_per_roughness": 0.0,       # measured -0.0000
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
    """The constants for VERSION (default: this Blender): its own measurement, else the newest
    one of the same major version not newer than it (the 3.4 measurement serves every 3.x);
    None where nothing was measured."""
    v = tuple((version or bpy.app.version)[:2])
    same = [k for k in MEASURED if k[0] == v[0] and k <= v] or [k for k in MEASURED if k[0] == v[0]]
    return MEASURED[max(same)] if same else None


def albedo_factor(albedo, roughness):
    """Rendered / requested diffuse albedo, per channel: k0(albedo) + k_per_roughness * roughness.
    It rises further toward grazing views (+2 % at 60 deg in 3.4)."""
    c = measurement()
    if c is None:
        return [1.0] * len(albedo)
    r = min(max(roughness, 0.0), 1.0)
    if bpy.app.version < (4, 0, 0):        # k at the wanted albedo (k varies by 1.5 % in 3.4)
        return [_interp(c["albedo"], c["k0"], a) + c["k_per_roughness"] * r for a in albedo]
    out = []
    for a in albedo:                       # k at the Base Colour b = a / k that renders a
        k = 1.0
        for _ in range(30):
            k = _interp(c["albedo"], c["k0"], a / k) + c["k_per_roughness"] * r
        out.append(k)
    return out


def sss_albedo_factor(albedo):
    """Rendered / requested albedo of the Principled random-walk subsurface closure (roughness 0)
    under a sun: k0 is its white-furnace value, which includes the exit's Disney light falloff,
    whose cosine-weighted mean is 1 - 1/42."""
    c = measurement()
    if c is None:
        return 1.0
    return _interp(c["albedo"], [k / (1.0 - 1.0 / 42.0) for k in c["k0"]], albedo)
