"""A Mitsuba 3 scene from a `skinbake export mitsuba` directory.

The export holds scene.json (camera, lights, skins, objects in the scene's
left-handed frame), the meshes as PLY already in Mitsuba's right-handed frame
((x, y, z) -> (x, y, -z)) and manifest.json (the mode, each object's PLY and
skin, each skin's bake). The skin is either
  table       the baked table (tablebsdf.TableBSDF) on the surface, or
  volumetric  the bake's layers (manifest.json of the bake, per wavelength) as
              homogeneous media in shells under the surface: shell k is the
              mesh moved inward along its vertex normals by the depth of the
              top of layer k; each shell is a smooth dielectric where n changes
              (null where it does not) with the layer above as exterior and
              the layer below as interior; the innermost shell is a black
              absorber (the bake's clear half space below the last layer,
              which never returns light).
Two practical limits of a float32 ray tracer are handled and said on stderr:
  * Mitsuba moves a new ray off a surface by about 9e-5 x (1 + |p|). The
    scene is moved so that the camera's look_at is the origin, and a clear
    layer thinner than 4 such offsets (the sebum film: 10 um against about
    13 um at a head's size in mm) is left out; the surface then refracts
    straight into the next layer's index (the film adds about 0.01 to the
    mirror reflection, none of which is in the diffuse light).
  * Where the body is thinner than twice the layers (ears, nostrils), the
    depths at a vertex are scaled down to 0.45 of the distance to the
    opposite surface (cast along -n), so that shells never cross.
Point lights in scene files do not fade with distance; Mitsuba's do (1/d^2):
a point light's intensity is its irradiance times d^2, d its distance to the
camera's look_at, exact there and within (d/(d +- r))^2 over an object of
radius r.
"""
import math
import os
import shutil
import sys
import tempfile

import numpy as np

from . import json_load

RAY_EPS = 8.9e-5   # Mitsuba's RayEpsilon for float32 (1500 ulp of 1)


def _note(text):
    sys.stderr.write("skinbake_mitsuba: %s\n" % text)


def _f(v):
    """scene.json frame -> Mitsuba frame."""
    return np.array([v[0], v[1], -v[2]], dtype=float)


def read_ply(path):
    """(positions [n][3], normals [n][3], faces [m][3]) of a PLY written by
    skinbake export mitsuba (binary little endian, float x y z nx ny nz [u v])."""
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline().decode("ascii").strip()
            header.append(line)
            if line == "end_header":
                break
        nv = nf = 0
        props = []
        for line in header:
            w = line.split()
            if w[:2] == ["element", "vertex"]:
                nv = int(w[2])
            elif w[:2] == ["element", "face"]:
                nf = int(w[2])
            elif w[:2] == ["property", "float"]:
                props.append(w[2])
        v = np.frombuffer(f.read(4 * len(props) * nv), dtype="<f4").reshape(nv, len(props))
        rec = np.dtype([("n", "u1"), ("i", "<i4", (3,))])
        faces = np.frombuffer(f.read(rec.itemsize * nf), dtype=rec)["i"]
    return v[:, 0:3].astype(float), v[:, 3:6].astype(float), faces.astype(np.int64)


def write_ply(path, pos, nrm, faces):
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                 "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face %d\n"
                 "property list uchar int vertex_indices\nend_header\n" % (len(pos), len(faces))).encode("ascii"))
        f.write(np.hstack([pos, nrm]).astype("<f4").tobytes())
        rec = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<i4", (3,))])
        rec["n"] = 3
        rec["i"] = faces
        f.write(rec.tobytes())


def _bake_layers(bake):
    with open(os.path.join(bake, "manifest.json")) as f:
        man = json_load(f)
    return man


def _inward_thickness(pos, nrm, faces):
    """Distance from each vertex to the opposite side of the closed mesh along -n."""
    import mitsuba as mi
    import drjit as dr
    mesh = mi.Mesh("probe", len(pos), len(faces))
    params = mi.traverse(mesh)
    params["vertex_positions"] = mi.Float(pos.astype(np.float32).ravel())
    params["faces"] = mi.UInt32(faces.astype(np.uint32).ravel())
    params.update()
    scene = mi.load_dict({"type": "scene", "m": mesh})
    scale = 1.0 + np.abs(pos).max()
    o = pos - nrm * (4.0 * RAY_EPS * scale)
    ray = mi.Ray3f(mi.Point3f(*[mi.Float(o[:, k].astype(np.float32)) for k in range(3)]),
                   mi.Vector3f(*[mi.Float((-nrm[:, k]).astype(np.float32)) for k in range(3)]))
    si = scene.ray_intersect(ray)
    t = np.array(dr.select(si.is_valid(), si.t, 1e30))
    return t


def _medium(layer, unit_cm, spectral, chan_wl, channel=None):
    """A homogeneous medium of one layer over the bake's wavelengths, or None
    (clear). Coefficients [1/cm] become 1/unit."""
    mua = np.array([ly["mua_per_cm"] for ly in layer]) * unit_cm
    mus = np.array([ly["mus_per_cm"] for ly in layer]) * unit_cm
    g = float(np.mean([ly["g"] for ly in layer]))
    if np.all(mua == 0.0) and np.all(mus == 0.0):
        return None
    mut = mua + mus
    alb = np.where(mut > 0, mus / np.where(mut > 0, mut, 1.0), 0.0)
    if channel is not None:
        # one wavelength, grey: no chromatic distance sampling
        k = chan_wl[channel]
        return {"type": "homogeneous", "sigma_t": float(mut[k]), "albedo": float(alb[k]),
                "phase": {"type": "hg", "g": g}}
    if spectral is not None:
        wl = list(spectral)
        def spec(v):
            # flat beyond the bake's wavelengths (an irregular spectrum is 0 outside its range)
            pts = [(360.0, float(v[0]))] + [(float(w), float(x)) for w, x in zip(wl, v)] + [(830.0, float(v[-1]))]
            return {"type": "irregular", "wavelengths": ",".join("%g" % p[0] for p in pts),
                    "values": ",".join("%.9g" % p[1] for p in pts)}
        return {"type": "homogeneous", "sigma_t": spec(mut), "albedo": spec(alb), "phase": {"type": "hg", "g": g}}
    # rgb values above 1 are refused as reflectances: sigma_t as a colour in
    # [0, 1] times the medium's scale
    top = float(max(mut[k] for k in chan_wl))
    sig = {"type": "rgb", "value": [float(mut[k]) / top for k in chan_wl]}
    al = {"type": "rgb", "value": [float(alb[k]) for k in chan_wl]}
    return {"type": "homogeneous", "sigma_t": sig, "scale": top, "albedo": al, "phase": {"type": "hg", "g": g}}


def _shells(name, ply, centre, view_dist, bake, unit_mm, tmp, spectral, channel=None):
    """Scene-dict shapes of a volumetric skin on mesh PLY, moved by -centre."""
    import mitsuba as mi
    man = _bake_layers(bake)
    per_wl = man["layers"]                      # [wavelength]{layers: [...]}
    n_layers = len(per_wl[0]["layers"])
    layers = [[w["layers"][k] for w in per_wl] for k in range(n_layers)]   # [layer][wavelength]
    n_below = float(np.mean([w["n_below"] for w in per_wl]))
    unit_cm = unit_mm / 10.0
    pos, nrm, faces = read_ply(ply)
    pos = pos - centre[None, :]
    # the offset where it is seen: the vertices within half the camera distance
    r = np.abs(pos).max(axis=1)
    near = r[r < 0.5 * view_dist]
    eps = RAY_EPS * (1.0 + (near.max() if len(near) else r.max()))
    keep = []
    for k, ly in enumerate(layers):
        clear = all(x["mua_per_cm"] == 0.0 and x["mus_per_cm"] == 0.0 for x in ly)
        d_units = ly[0]["d_cm"] / unit_cm
        if clear and d_units < 4.0 * eps:
            _note("%s: the clear layer %d (%.4g um) is thinner than 4 ray offsets (%.3g um): left out"
                  % (name, k, ly[0]["d_cm"] * 1e4, eps * unit_mm * 1e3))
            continue
        keep.append(ly)
    rgb_from_wl = np.array(man["rgb"]["rgb_from_wl"]).reshape(3, len(per_wl))
    chan_wl = [int(np.argmax(rgb_from_wl[c])) for c in range(3)]
    depths = np.cumsum([0.0] + [ly[0]["d_cm"] / unit_cm for ly in keep])   # top of each layer, then bottom
    thick = _inward_thickness(pos, nrm, faces)
    squeeze = np.minimum(1.0, 0.45 * thick / depths[-1])
    if np.any(squeeze < 1.0):
        _note("%s: layers squeezed at %d of %d vertices where the body is thinner than %.3g units"
              % (name, int(np.sum(squeeze < 1.0)), len(pos), 2 * depths[-1] / 0.45))
    media = [_medium(ly, unit_cm, spectral, chan_wl, channel) for ly in keep]
    alpha = float(man["specular"]["alpha"])
    ns = [float(np.mean([x["n"] for x in ly])) for ly in keep]
    shapes = {}
    n_prev = 1.0
    above = None
    for k in range(len(keep) + 1):
        p = pos - nrm * (depths[k] * squeeze)[:, None]
        path = os.path.join(tmp, "%s_shell%d.ply" % (name, k))
        write_ply(path, p, nrm, faces)
        if k < len(keep):
            if k == 0 and alpha > 0.0:
                # the bake's rough surface (its GGX specular lobe); a rough boundary
                # also lets the path tracer reach point lights from under the skin
                bsdf = {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha,
                        "int_ior": ns[0], "ext_ior": n_prev}
            elif ns[k] == n_prev:
                bsdf = {"type": "null"}
            else:
                bsdf = {"type": "dielectric", "int_ior": ns[k], "ext_ior": n_prev}
            below = media[k]
            n_prev = ns[k]
        else:
            bsdf = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.0, 0.0, 0.0]}}
            below = None
        shape = {"type": "ply", "filename": path, "bsdf": bsdf, "face_normals": False}
        if above is not None:
            shape["exterior"] = above
        if below is not None:
            shape["interior"] = below
        shapes["%s_shell%d" % (name, k)] = shape
        above = below
    if n_below != ns[-1]:
        _note("%s: the bake's half space below has n %.3g, not the last layer's %.3g: the innermost shell "
              "absorbs without a Fresnel boundary" % (name, n_below, ns[-1]))
    return shapes, keep, (alpha, ns[0])


def _max_depth(keep):
    from . import stack as stk
    layers = []
    for ly in keep:
        for x in ly:
            layers.append(stk.Layer(d=x["d_cm"], n=x["n"], mua=x["mua_per_cm"], mus=x["mus_per_cm"], g=x["g"]))
    return stk.max_depth(layers)


def _translucent(name, ply, centre, bake, fitdir, unit_mm, channel):
    """Scene-dict shape of a translucent skin (transbsdf.py, transfit.py) on mesh PLY."""
    import mitsuba as mi
    with open(os.path.join(fitdir, "fit.json")) as f:
        fit = json_load(f)
    if os.path.realpath(fit["bake"]) != os.path.realpath(bake):
        raise ValueError("object '%s': --fit %s was fitted to the bake %s, not to its bake %s"
                         % (name, fitdir, fit["bake"], bake))
    ch = fit["channels"][channel]
    unit_cm = unit_mm / 10.0
    medium = {"type": "homogeneous", "sigma_t": float(ch["mu_t_per_cm"]) * unit_cm,
              "albedo": float(ch["albedo"]), "phase": {"type": "isotropic"}}
    shape = {"type": "ply", "filename": ply, "face_normals": False,
             "to_world": mi.ScalarTransform4f().translate((-centre).tolist()),
             "bsdf": {"type": "skinbake_translucent", "bake": bake, "fit": fitdir,
                      "channel": channel},
             "interior": medium}
    return shape, (float(fit["alpha"]), float(fit["n"])), float(ch["albedo"])


def build(export_dir, mode, width=None, spp=64, tmp=None, channel=None, estimator="exit",
          fitdir=None):
    """The scene dict of the export in mode 'table' or 'volumetric' with the
    current variant; tmp: a directory for the shells (volumetric); channel
    (mono variants): 0, 1, 2 for R, G, B, each the bake wavelength with the
    largest weight in that channel."""
    import mitsuba as mi
    with open(os.path.join(export_dir, "manifest.json")) as f:
        man = json_load(f)
    with open(os.path.join(export_dir, "scene.json")) as f:
        sc = json_load(f)
    if man.get("format") != "skinbake-mitsuba":
        raise ValueError("%s is not a skinbake export mitsuba directory" % export_dir)
    # the translucent mode needs closed meshes, as the volumetric one
    allowed = ("both", "volumetric", "translucent") if mode == "translucent" else ("both", mode)
    if man["mode"] not in allowed:
        raise ValueError("%s was exported for mode %s, not %s" % (export_dir, man["mode"], mode))
    cam = sc["camera"]
    centre = _f(cam["look_at"])
    w = width or sc["width_px"]
    h = max(1, int(round(w * sc["height_px"] / sc["width_px"])))
    if channel is not None:
        rgb = (lambda v: {"type": "spectrum", "value": float(v[channel])})
    elif mi.is_rgb:
        rgb = (lambda v: {"type": "rgb", "value": [float(x) for x in v]})
    else:
        rgb = (lambda v: {"type": "spectrum", "value": float(np.mean(v))})
    film = {"type": "hdrfilm", "width": w, "height": h, "rfilter": {"type": "box"},
            "pixel_format": "luminance" if channel is not None else "rgb"}
    to_cam = mi.ScalarTransform4f().look_at(origin=(_f(cam["location"]) - centre).tolist(), target=[0.0, 0.0, 0.0],
                                           up=[0.0, 1.0, 0.0])
    if cam["type"] == "perspective":
        sensor = {"type": "perspective", "fov": cam["horizontal_fov_deg"], "fov_axis": "x", "to_world": to_cam}
    else:
        sensor = {"type": "orthographic", "to_world": to_cam @ mi.ScalarTransform4f().scale([cam["width"] / 2] * 3)}
    sensor["film"] = film
    sensor["sampler"] = {"type": "independent", "sample_count": spp}
    scene = {"type": "scene", "sensor": sensor}
    if any(v > 0 for v in sc["background_rgb"]):
        scene["background"] = {"type": "constant", "radiance": rgb(sc["background_rgb"])}
    for i, L in enumerate(sc["lights"]):
        if L["type"] == "parallel":
            scene["light_%d" % i] = {"type": "directional", "direction": _f(L["direction"]).tolist(),
                                     "irradiance": rgb(L["irradiance_rgb"])}
        else:
            p = _f(L["position"]) - centre
            d2 = float(p @ p)
            scene["light_%d" % i] = {"type": "point", "position": p.tolist(),
                                     "intensity": rgb([v * d2 for v in L["irradiance_rgb"]])}
        if L.get("area_size", 0) > 0:
            _note("light '%s': the area light is rendered as a point light" % L["name"])
    skins = {s["name"]: s for s in man["skins"]}
    objs = {o["name"]: o for o in man["objects"]}
    bake_of = {}
    depth = 8
    top = None
    for ob in sc["objects"]:
        name = ob["name"]
        mo = objs[name]
        mat = ob["material"]
        if mat == "skin":
            bake = skins[ob["skin"]]["bake"]
            bake_of[name] = bake
        elif mat in ("plain", "model"):
            col = ob["color"] if mat == "plain" else mo["model_diffuse_rgb"]
            bsdf = {"type": "diffuse", "reflectance": rgb(col)}
        else:
            raise ValueError("object '%s': material %s is not rendered by skinbake_mitsuba (skin, plain, model)"
                             % (name, mat))
        if ob["shape"] == "mesh":
            ply = os.path.join(export_dir, mo["ply"])
            if mat == "skin" and mode == "translucent":
                shape, top, albedo = _translucent(name, ply, centre, bake, fitdir, sc["unit_mm"],
                                                  channel)
                scene[name] = shape
                from . import stack as stk
                depth = max(depth, stk.max_depth([stk.Layer(d=1.0, mua=1.0 - albedo, mus=albedo)]))
                continue
            if mat == "skin" and mode == "volumetric":
                spectral = None
                if mi.is_spectral:
                    spectral = _bake_layers(bake)["wavelengths_nm"]
                view_dist = float(np.linalg.norm(_f(cam["location"]) - centre))
                shapes, keep, top = _shells(name, ply, centre, view_dist, bake, sc["unit_mm"], tmp,
                                            spectral, channel)
                scene.update(shapes)
                depth = max(depth, _max_depth(keep))
                continue
            shape = {"type": "ply", "filename": ply, "face_normals": False,
                     "to_world": mi.ScalarTransform4f().translate((-centre).tolist())}
        elif ob["shape"] == "sphere":
            m = np.array(ob["to_world"])
            c = _f((m @ np.array(list(ob["center"]) + [1.0]))[:3]) - centre
            shape = {"type": "sphere", "center": c.tolist(), "radius": ob["radius"] * ob["scale"]}
            if mat == "skin" and mode in ("volumetric", "translucent"):
                raise ValueError("object '%s': %s spheres are not written yet (meshes are)"
                                 % (name, mode))
        else:
            raise ValueError("object '%s': shape %s is not rendered by skinbake_mitsuba" % (name, ob["shape"]))
        if mat == "skin":
            shape["bsdf"] = {"type": "skinbake_table", "bake": bake}
        else:
            shape["bsdf"] = bsdf
        scene[name] = shape
    layered = mode in ("volumetric", "translucent")
    if layered and top is not None and top[0] > 0.0 and estimator == "exit":
        # exitnee.py: the light through the rough top estimated at every medium vertex
        scene["integrator"] = {"type": "skinbake_volpath", "max_depth": depth, "rr_depth": 1 << 30,
                               "alpha": top[0], "eta": top[1]}
    elif mode in ("volumetric", "translucent"):
        scene["integrator"] = {"type": "volpath", "max_depth": depth, "rr_depth": 1 << 30}
    else:
        scene["integrator"] = {"type": "path", "max_depth": 8}
    return scene


def render(export_dir, mode, out, width=None, spp=64, variant_name=None, seed=0, fitdir=None,
           estimator="exit"):
    """Render the export to OUT (.exr: linear; .png: sRGB 8-bit); returns
    (seconds, variant). Volumetric mode renders R, G and B apart in a mono
    variant, each with its wavelength's grey media: in an rgb variant the
    media's colour makes Mitsuba sample distances by one channel and weight
    the others by exponentials of the path length (coloured fireflies)."""
    import time
    from . import variant
    per_channel = mode in ("volumetric", "translucent") and variant_name is None
    used = variant.choose("mono" if per_channel else "rgb", variant_name)
    import mitsuba as mi
    from . import tablebsdf
    tablebsdf.register()
    from . import exitnee, transbsdf
    exitnee.register()
    transbsdf.register()
    tmp = tempfile.mkdtemp(prefix="skinbake-mitsuba-")
    try:
        t0 = time.time()
        if per_channel:
            chans = []
            for c in range(3):
                scene = mi.load_dict(build(export_dir, mode, width, spp, tmp, channel=c,
                                           fitdir=fitdir, estimator=estimator))
                chans.append(np.array(mi.render(scene, spp=spp, seed=seed))[..., 0])
            arr = np.stack(chans, axis=-1)
        else:
            scene = mi.load_dict(build(export_dir, mode, width, spp, tmp))
            arr = np.array(mi.render(scene, spp=spp, seed=seed))   # forces the (lazy) render
        seconds = time.time() - t0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    bmp = mi.Bitmap(arr.astype(np.float32), mi.Bitmap.PixelFormat.RGB)
    if out.endswith(".png"):
        bmp = bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True)
    bmp.write(out)
    return seconds, used + (" (R, G, B apart)" if per_channel else "")
