"""Measurements of the translucent mode in Mitsuba itself, on a flat slab 20 cm
wide and 10 cm deep over a black bottom (scene unit cm) with the translucent surface
(transbsdf.py) and the fitted medium inside (transfit.py), one colour channel.
  flat     the BRDF under a distant light: a radiancemeter's radiance along
           (theta_o, delta_phi) divided by cos(theta_i), light of irradiance 1
           from theta_i (delta_phi = 0: the view back toward the light), to be
           compared with skinbake eval at the channel's wavelength;
  rings    the profile R(r) by measure.rd_ring's reciprocal ring emitter, to be
           compared with the bake's Rd(r) (the bake's specular lobe left out, as
           Rd excludes it; the first ring includes the remainder's light, which
           leaves where it enters).
Values come with standard errors from independent batches."""
import math
import os

import numpy as np

from . import json_load
from . import measure

HALF_WIDTH_CM = 10.0
DEPTH_CM = 10.0


def _base(bake, fitdir, channel, profile=False):
    import mitsuba as mi
    with open(os.path.join(fitdir, "fit.json")) as f:
        fit = json_load(f)
    ch = fit["channels"][channel]
    from . import stack as stk
    medium = {"type": "homogeneous", "sigma_t": float(ch["mu_t_per_cm"]),
              "albedo": float(ch["albedo"]), "phase": {"type": "isotropic"}}
    bsdf = {"type": "skinbake_translucent", "bake": bake, "fit": fitdir, "channel": channel,
            "specular": not profile}
    # analytic rectangles as stack.py (a mesh 20 cm wide intersects too coarsely for the
    # ring emitter 1e-3 cm above it)
    top = stk._rect(0.0, bsdf, None, medium, HALF_WIDTH_CM)
    black = {"type": "diffuse", "reflectance": 0.0}
    bottom = stk._rect(-DEPTH_CM, black, medium, None, HALF_WIDTH_CM)
    depth = stk.max_depth([stk.Layer(d=1.0, mua=1.0 - ch["albedo"], mus=ch["albedo"])])
    integ = {"type": "skinbake_volpath", "max_depth": depth, "rr_depth": 1 << 30,
             "alpha": float(fit["alpha"]), "eta": float(fit["n"])}
    if profile:
        # the ring emitter is 1e-3 cm above the surface: volpath's MIS between light and
        # BSDF sampling there (exitnee.py's estimate through the surface has no MIS: fireflies)
        integ = {"type": "volpath", "max_depth": depth, "rr_depth": 1 << 30}
    return {"type": "scene", "integrator": integ, "top": top, "bottom": bottom}


def _register():
    from . import exitnee, transbsdf
    exitnee.register()
    transbsdf.register()


def flat(bake, fitdir, channel, points, spp=4096, batches=8):
    """[(fr, err)] [1/sr] for each (theta_i, theta_o, delta_phi) in degrees."""
    _register()
    out = []
    for ti, to, dp in points:
        scene = _base(bake, fitdir, channel)
        wl = measure._direction(ti, 0.0)
        wv = measure._direction(to, dp)
        scene["light"] = {"type": "directional", "direction": (-wl).tolist(),
                          "irradiance": {"type": "spectrum", "value": 1.0}}
        scene["sensor"] = measure._sensor(wv * measure.SENSOR_CM, -wv, spp)
        mean, err = measure._render(scene, spp, batches)
        c = math.cos(math.radians(ti))
        out.append((mean / c, err / c))
    return out


def rings(bake, fitdir, channel, edges, spp=4096, batches=8):
    """[(power, err)] leaving between consecutive edges [cm] for a normal beam."""
    _register()
    base = _base(bake, fitdir, channel, profile=True)
    return [measure.rd_ring(None, r0, r1, spp, batches, base=base)
            for r0, r1 in zip(edges, edges[1:])]


def bake_rings(bake, k, edges):
    """The bake's ring powers between edges [cm] at wavelength index k (its
    profile's bins split by area)."""
    with open(os.path.join(bake, "manifest.json")) as f:
        rad = json_load(f)["radial"]
    dr = float(rad["dr_cm"])
    rd = np.array(rad["rd_r"][k], dtype=float)
    e = dr * np.arange(len(rd) + 1)
    cum = np.concatenate([[0.0], np.cumsum(rd * math.pi * (e[1:] ** 2 - e[:-1] ** 2))])
    # within a bin the power grows with the area: interpolate in r^2
    c = np.interp(np.square(edges), e ** 2, cum)
    return list(np.diff(c))
