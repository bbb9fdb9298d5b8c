"""Calibration constants of the general mode, measured per Blender version and stored with the
version they were measured on.  A version without a measurement gets factor 1 (no correction)."""
import bpy

# The subsurface closure of the general mode's fitted mixture on Blender 4+ (general.py) has these
# fixed inputs, the ones VIEW_RESPONSE was measured with.
VIEW_IOR = 1.4
VIEW_ROUGHNESS = 0.02

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


# Below what radius, in pixel footprints (footprint.py), Cycles renders a subsurface channel as a
# Lambert diffuse of its colour instead of the random walk: None where only below 1e-8 m.
# Measured with a closed box of the subsurface closure under a sun, radii 0.1-1 pixels
# (orthographic and perspective, cos_view 1 and 0.45): 4.3.0 renders exactly the Base Colour (the
# Lambert response) at 0.249 px and the walk at 0.25 px and above, 4.2.23 alike; 4.4.0 and 4.5.15
# the walk at 0.01-0.26 px.
# The shipped kernel sources agree: 4.2's and 4.3's bssrdf_setup have
# max(0.25 sd->dP, BSSRDF_MIN_RADIUS), 3.4's, 4.4's, 4.5's and 5.0's BSSRDF_MIN_RADIUS (1e-8) alone.
SSS_DIFFUSE_BELOW = {
    (3, 4): {"pixels": None, "measured_with": "Blender 3.4.1 (Debian 12): kernel source"},
    (4, 2): {"pixels": 0.25, "measured_with": "Blender 4.2.23 LTS (bpy), Cycles CPU, 24 px, 16 spp; kernel source"},
    (4, 3): {"pixels": 0.25, "measured_with": "Blender 4.3.0 (bpy), Cycles CPU, 24 px, 16 spp; kernel source "
                                              "(Debian 13's 4.3.2: the sphere of tests/blender_lights.sh)"},
    (4, 4): {"pixels": None, "measured_with": "Blender 4.4.0 (bpy), Cycles CPU, 24 px, 16 spp; kernel source"},
    (4, 5): {"pixels": None, "measured_with": "Blender 4.5.15 LTS (bpy), Cycles CPU, 24 px, 16 spp; kernel source"},
    (5, 0): {"pixels": None, "measured_with": "Blender 5.0.1 (bpy): kernel source"},
}


def sss_diffuse_below_pixels(version=None):
    """SSS_DIFFUSE_BELOW's footprints for VERSION (default: this Blender): its own measurement, else
    the newest of the same major version not newer than it; where there is none (4.0, 4.1: no
    wheels to measure), a quarter pixel, since raising a radius to it costs at most a sub-pixel blur.
    None: no such fall-back."""
    v = tuple((version or bpy.app.version)[:2])
    older = [k for k in SSS_DIFFUSE_BELOW if k[0] == v[0] and k <= v]
    return SSS_DIFFUSE_BELOW[max(older)]["pixels"] if older else 0.25


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
    return _version_entry(MEASURED, version)


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


# Blender 4+: pi L / E per unit Base Colour, k(base, cos_view), of the Principled BSDF with
# random-walk subsurface (weight 1, scale 1, IOR VIEW_IOR, roughness VIEW_ROUGHNESS, specular IOR
# level 0) on a wide closed box under a sun along the normal: rows per "cos_view", columns per
# "base".  4.x and 5.x render this closure with the exact cosine law in the light (sun60_vs_sun0:
# the same at a sun 60 deg off the normal, relative difference at cos_view 0.3 and 1 for Base
# Colours 0.02, 0.1, 0.45), so R(base, cos_view) = base k is the whole response; it rises toward
# grazing views and falls with the Base Colour (the random walk's albedo inversion).
VIEW_RESPONSE = {
    (4, 5): {
        "measured_with": "Blender 4.5.15 LTS, Cycles CPU, 24 px, 512 spp (scripts/blender-calibrate.py -- view)",
        "base": (0.005, 0.01, 0.02, 0.035, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25, 0.3, 0.45, 0.6, 0.8, 1.0),
        "cos_view": (0.1, 0.2, 0.3, 0.45, 0.6, 0.75, 0.9, 1.0),
        "k": (
            (1.7666, 1.7605, 1.7193, 1.6511, 1.6009, 1.5770, 1.5556, 1.5107, 1.4680, 1.4271, 1.3882, 1.2844, 1.1944, 1.0945, 0.9508),   # cos_view 0.1
            (1.6037, 1.5981, 1.5607, 1.4992, 1.4546, 1.4389, 1.4241, 1.3938, 1.3643, 1.3345, 1.3077, 1.2306, 1.1608, 1.0807, 0.9457),   # cos_view 0.2
            (1.4489, 1.4439, 1.4101, 1.3558, 1.3163, 1.3071, 1.2979, 1.2796, 1.2612, 1.2413, 1.2239, 1.1725, 1.1234, 1.0652, 0.9399),   # cos_view 0.3
            (1.2595, 1.2552, 1.2258, 1.1779, 1.1445, 1.1417, 1.1396, 1.1339, 1.1278, 1.1193, 1.1123, 1.0917, 1.0693, 1.0416, 0.9309),   # cos_view 0.45
            (1.1113, 1.1075, 1.0816, 1.0402, 1.0113, 1.0128, 1.0133, 1.0159, 1.0179, 1.0183, 1.0188, 1.0207, 1.0197, 1.0187, 0.9218),   # cos_view 0.6
            (0.9942, 0.9908, 0.9676, 0.9310, 0.9056, 0.9096, 0.9114, 0.9193, 0.9268, 0.9340, 0.9400, 0.9584, 0.9743, 0.9967, 0.9126),   # cos_view 0.75
            (0.8979, 0.8948, 0.8739, 0.8416, 0.8190, 0.8244, 0.8288, 0.8401, 0.8512, 0.8606, 0.8715, 0.9030, 0.9330, 0.9756, 0.9034),   # cos_view 0.9
            (0.8468, 0.8439, 0.8241, 0.7930, 0.7719, 0.7781, 0.7825, 0.7954, 0.8082, 0.8192, 0.8321, 0.8699, 0.9074, 0.9621, 0.8972),   # cos_view 1.0
        ),
        "sun60_vs_sun0": (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    },
    (5, 0): {
        "measured_with": "Blender 5.0.1, Cycles CPU, 24 px, 512 spp (scripts/blender-calibrate.py -- view)",
        "base": (0.005, 0.01, 0.02, 0.035, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25, 0.3, 0.45, 0.6, 0.8, 1.0),
        "cos_view": (0.1, 0.2, 0.3, 0.45, 0.6, 0.75, 0.9, 1.0),
        "k": (
            (1.7725, 1.7663, 1.7250, 1.6567, 1.6062, 1.5822, 1.5610, 1.5150, 1.4714, 1.4261, 1.3898, 1.2859, 1.1952, 1.0950, 0.9508),   # cos_view 0.1
            (1.6097, 1.6041, 1.5666, 1.5058, 1.4610, 1.4447, 1.4305, 1.3988, 1.3682, 1.3339, 1.3086, 1.2314, 1.1612, 1.0813, 0.9458),   # cos_view 0.2
            (1.4513, 1.4463, 1.4125, 1.3584, 1.3188, 1.3095, 1.3017, 1.2825, 1.2635, 1.2400, 1.2251, 1.1737, 1.1240, 1.0658, 0.9400),   # cos_view 0.3
            (1.2578, 1.2534, 1.2241, 1.1787, 1.1454, 1.1429, 1.1420, 1.1357, 1.1290, 1.1172, 1.1129, 1.0924, 1.0697, 1.0422, 0.9311),   # cos_view 0.45
            (1.1073, 1.1034, 1.0776, 1.0390, 1.0103, 1.0123, 1.0138, 1.0160, 1.0177, 1.0154, 1.0188, 1.0211, 1.0200, 1.0194, 0.9221),   # cos_view 0.6
            (0.9918, 0.9884, 0.9652, 0.9304, 0.9051, 0.9094, 0.9131, 0.9207, 0.9277, 0.9316, 0.9401, 0.9592, 0.9750, 0.9975, 0.9130),   # cos_view 0.75
            (0.8981, 0.8950, 0.8740, 0.8429, 0.8204, 0.8265, 0.8314, 0.8424, 0.8530, 0.8610, 0.8734, 0.9047, 0.9340, 0.9764, 0.9037),   # cos_view 0.9
            (0.8420, 0.8391, 0.8195, 0.7907, 0.7698, 0.7766, 0.7831, 0.7959, 0.8085, 0.8177, 0.8322, 0.8706, 0.9080, 0.9631, 0.8978),   # cos_view 1.0
        ),
        "sun60_vs_sun0": (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    },
}


def _version_entry(table, version=None):
    """TABLE's entry for VERSION (default: this Blender): its own, else the newest of the same major
    version not newer than it, else any of the same major version; None where nothing was measured."""
    v = tuple((version or bpy.app.version)[:2])
    same = [k for k in table if k[0] == v[0] and k <= v] or [k for k in table if k[0] == v[0]]
    return table[max(same)] if same else None


def view_measurement(version=None):
    return _version_entry(VIEW_RESPONSE, version)


def view_response(base, cos_view, c=None):
    """R(base, cos_view) of the measured table C (default: this Blender's), linear in cos_view and in
    base between the nodes (the end values beyond them)."""
    c = c or view_measurement()
    cvs = c["cos_view"]
    row = [_interp(cvs, [r[i] for r in c["k"]], cos_view) for i in range(len(c["base"]))]
    return base * _interp(c["base"], row, base)


def base_for_response(target, cos_view, c=None):
    """The Base Colour whose response at COS_VIEW is TARGET (bisection: R rises with the base), and
    whether it was reachable (False: TARGET is above the response of Base Colour 1, which is used)."""
    c = c or view_measurement()
    lo, hi = 0.0, 1.0
    if view_response(hi, cos_view, c) < target:
        return hi, False
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        if view_response(mid, cos_view, c) < target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi), True
