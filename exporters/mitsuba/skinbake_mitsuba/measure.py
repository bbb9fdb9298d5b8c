"""Flat-slab measurements with Mitsuba's volumetric path tracer, by reciprocity.

A unidirectional path tracer cannot connect a delta light through a smooth
dielectric, so each quantity of skinbake simulate is measured from the other
end: a radiancemeter looks at the slab and the light is an extended emitter.
  Rd(theta)  radiance leaving along theta under a constant environment of
             radiance 1 is the albedo for incidence at theta (reciprocity),
             Rd + Rsp; Rsp is the closed form of stack.specular_rsp.
  Rd(r)      a one-sided disk (or ring) emitter of radiance 1 facing down, GAP_CM
             above the surface, black on both sides; the radiancemeter between
             looks straight down at the centre. The radiance is the fraction of
             a normally incident beam at the centre that leaves through the
             disk (all exit directions): C(r), plus Rsp for a full disk.
  BRDF bands an environment lit only in a band of polar angles (all azimuths);
             the radiance along the view divided by the band's projected solid
             angle is the azimuthal mean BRDF (brdf_az) over the band. A small
             distant cone instead of a band is hit by too few paths (nothing can
             aim at it through the smooth boundary): 20 % errors at 65k paths.
Every value comes with a standard error from independent batches (seeds).
"""
import math
import os
import shutil
import tempfile

import numpy as np

from . import stack as stk

GAP_CM = 1e-3          # emitter height: 3e-5 is inside the ray epsilon, 1e-4 biased high
SENSOR_CM = 1.0        # radiancemeter distance for the angular measurements
ENV_FLOOR = 1e-6       # radiance outside a band environment (see _band_envmap)


def _sensor(origin, direction, spp):
    return {"type": "radiancemeter", "origin": list(map(float, origin)),
            "direction": list(map(float, direction)),
            "film": {"type": "hdrfilm", "width": 1, "height": 1, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": spp}}


def _integrator(layers):
    return {"type": "volpath", "max_depth": stk.max_depth(layers), "rr_depth": 1 << 30}


def _render(scene_dict, spp, batches):
    """Mean and standard error over batches of the single pixel's value."""
    import mitsuba as mi
    scene = mi.load_dict(scene_dict)
    vals = []
    for b in range(batches):
        img = mi.render(scene, seed=b, spp=spp)
        vals.append(float(np.array(img).reshape(-1)[0]))
    vals = np.array(vals)
    return float(vals.mean()), float(vals.std(ddof=1) / math.sqrt(len(vals)))


def _direction(theta_deg, phi_deg=0.0):
    t = math.radians(theta_deg)
    p = math.radians(phi_deg)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def rd_theta(layers, theta_deg, spp=4096, batches=16, n_above=1.0, n_below=None):
    """Rd for incidence at theta_deg: (Rd, error, Rsp)."""
    scene = {"type": "scene", "integrator": _integrator(layers),
             "env": {"type": "constant", "radiance": {"type": "spectrum", "value": 1.0}}}
    scene.update(stk.slab_shapes(layers, n_above, n_below))
    w = _direction(theta_deg)
    scene["sensor"] = _sensor(w * SENSOR_CM, -w, spp)
    mean, err = _render(scene, spp, batches)
    rsp = stk.specular_rsp(layers, theta_deg, n_above)
    return mean - rsp, err, rsp


def _ring_obj(r0, r1, z, path, segments=256):
    """Write a flat ring r0 <= r <= r1 at height z facing down (-z) as OBJ."""
    phi = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    with open(path, "w") as f:
        for r in (r0, r1):
            for p in phi:
                f.write("v %.9g %.9g %.9g\n" % (r * math.cos(p), r * math.sin(p), z))
        for k in range(segments):
            k1 = (k + 1) % segments
            # clockwise seen from above, so the face normal points down
            f.write("f %d %d %d\n" % (k + 1, segments + k1 + 1, segments + k + 1))
            f.write("f %d %d %d\n" % (k + 1, k1 + 1, segments + k1 + 1))


def rd_ring(layers, r0, r1, spp=4096, batches=16, n_above=1.0, n_below=None, base=None):
    """Fraction of a normal beam's power leaving between radii r0 and r1 [cm]
    (Rsp excluded): (value, error). base: a scene dict (slab and integrator)
    to use instead of the layers' (then nothing is subtracted for Rsp)."""
    import mitsuba as mi
    if base is not None:
        scene = dict(base)
    else:
        scene = {"type": "scene", "integrator": _integrator(layers)}
        scene.update(stk.slab_shapes(layers, n_above, n_below))
    black = {"type": "diffuse", "reflectance": 0.0}
    emitter = {"type": "area", "radiance": {"type": "spectrum", "value": 1.0}}
    if r0 <= 0.0:
        scene["light"] = {"type": "disk", "bsdf": black, "emitter": emitter,
                          "to_world": mi.ScalarTransform4f().translate([0.0, 0.0, GAP_CM])
                          .scale([r1, r1, 1.0]).rotate([1.0, 0.0, 0.0], 180.0)}
    else:
        tmp = tempfile.mkdtemp(prefix="skinbake-mitsuba-")
        path = os.path.join(tmp, "ring.obj")
        _ring_obj(r0, r1, GAP_CM, path)
        scene["light"] = {"type": "obj", "filename": path, "face_normals": True,
                          "bsdf": black, "emitter": emitter}
    scene["sensor"] = _sensor([0.0, 0.0, 0.5 * GAP_CM], [0.0, 0.0, -1.0], spp)
    try:
        mean, err = _render(scene, spp, batches)
    finally:
        if r0 > 0.0:
            shutil.rmtree(tmp, ignore_errors=True)
    if r0 <= 0.0 and base is None:
        mean -= stk.specular_rsp(layers, 0.0, n_above)
    return mean, err


def _band_envmap(theta_lo, theta_hi, rows_per_degree=20):
    """An environment of radiance 1 for polar angles theta_lo..theta_hi from +z
    (deg), 0 elsewhere. The map is interpolated bilinearly: the edges ramp over
    one row (0.05 deg) symmetrically about theta_lo and theta_hi. Outside the
    band the radiance is FLOOR, not 0: with zero regions Mitsuba 3.9's envmap
    gave NaN on rare paths (1 batch in 8 of 8192 paths). FLOOR adds at most
    FLOOR (the slab's albedo times FLOOR) to the radiance, under 1e-4 of any
    band's signal."""
    import mitsuba as mi
    rows = 180 * rows_per_degree
    img = np.full((rows, 4, 3), ENV_FLOOR, dtype=np.float32)
    lo = int(round(theta_lo * rows_per_degree))
    hi = int(round(theta_hi * rows_per_degree))
    img[lo:hi] = 1.0
    # Mitsuba's lat-long map has its pole on +y: turn it to +z.
    return {"type": "envmap", "bitmap": mi.Bitmap(img),
            "to_world": mi.ScalarTransform4f().rotate([1.0, 0.0, 0.0], 90.0)}


def brdf_band(layers, theta_view, theta_lo, theta_hi, spp=4096, batches=16,
              n_above=1.0, n_below=None):
    """Azimuthal mean of the BRDF [1/sr] between the view direction theta_view and
    light from every azimuth in the polar band theta_lo..theta_hi (deg): the
    radiance along theta_view divided by the band's projected solid angle
    pi (sin^2 theta_hi - sin^2 theta_lo). By reciprocity it is skinbake
    simulate's brdf_az band theta_lo..theta_hi for incidence at theta_view.
    The band must not contain theta_view (the mirror reflection): (value, error)."""
    if theta_lo <= theta_view <= theta_hi:
        raise ValueError("the band holds the mirror direction of the view")
    scene = {"type": "scene", "integrator": _integrator(layers),
             "env": _band_envmap(theta_lo, theta_hi)}
    scene.update(stk.slab_shapes(layers, n_above, n_below))
    w = _direction(theta_view, 0.0)
    scene["sensor"] = _sensor(w * SENSOR_CM, -w, spp)
    mean, err = _render(scene, spp, batches)
    s_lo = math.sin(math.radians(theta_lo))
    s_hi = math.sin(math.radians(theta_hi))
    norm = math.pi * (s_hi * s_hi - s_lo * s_lo)
    return mean / norm, err / norm
