# Test helper, run inside Blender (pure Python, no numpy):
#   blender -b --factory-startup --python blender_scene.py -- make-lights OUT.blend
#       a user's file: an ellipsoid mesh "Head" (UVs, its own material), a perspective camera,
#       two suns, a point lamp and a spot lamp whose cone holds the head, black world
#   blender -b --factory-startup --python blender_scene.py -- make-keep OUT.blend SNAPSHOT.json
#       a richer user's file (meshes with materials, an empty in a collection, area lamp, hidden
#       lamp, world colour, a fake-user material, a scene property) and a snapshot of it
#   blender -b FILE.blend --python blender_scene.py -- check-keep SNAPSHOT.json
#       everything in the snapshot is still there and unchanged (Head's material and the lamps'
#       collections excepted); prints SKINBAKE_KEEP_OK or the differences
#   blender -b FILE.blend --python blender_scene.py -- material-summary NAME
#       prints SKINBAKE_VERSION and SKINBAKE_MATERIAL: material NAME's node and link counts and images
#   blender -b FILE.blend --python blender_scene.py -- measure-lights BRDF_HELPER BAKE OUT_STEM RES SAMPLES
#           [LO[:HI] [--ad]]
#       renders the imported file (exact mode: direct light only; point-sampled pixels) with normal
#       and position passes and compares each pixel with sum over lamps of E cos_l f_r, f_r from
#       BRDF_HELPER (bake_eval_rgb, as `skinbake eval`; with --ad adding-doubling point values of
#       the bake's stacks); prints SKINBAKE_LIGHTS n mean p95 max (each pixel's largest relative
#       error over RGB) and SKINBAKE_RING r g b (the render's sum over those pixels divided by the
#       reference's, per channel); with LO[:HI] only the pixels whose exit angle is in [LO, HI] deg
#       (the silhouettes)
#   blender -b FILE.blend --python blender_scene.py -- addon IMPORTER SET/manifest.json MESH
#       the add-on's File > Import operator (registered from IMPORTER) on the selected MESH in exact
#       mode; prints SKINBAKE_ADDON result material view-layers
#   blender -b --factory-startup --python blender_scene.py -- make-scene-json SCENE.json OUT.blend
#       the spheres of SCENE.json (scene.json of `skinbake scene`, plain materials) as smooth meshes
#       with Diffuse BSDFs, placed as the importer places scene.json's camera and lights; black
#       world, Cycles with direct light only (as POV-Ray without radiosity), point-sampled pixels
#   blender -b FILE.blend --python blender_scene.py -- scene-compare B.exr P.png SCENE.json
#       Blender's render B of FILE (radiance; camera and lights imported from SCENE.json) against
#       POV-Ray's P (16-bit linear, pi x radiance): pixels lit in one and not the other, the lit
#       areas and centroids, and over the 2 x 2 blocks lit in both with the pixels within 2 px of
#       them, the relative difference of pi B from P (a lone point light's 1/d^2 falloff taken
#       out per pixel); prints SKINBAKE_SILHOUETTE mismatched n_b n_p dx dy and
#       SKINBAKE_SHADING n mean p90
#   blender -b --factory-startup --python blender_scene.py -- footprint IMPORTER
#       the importer's pixel-footprint nodes (footprint.py, used on Blender 4.2-4.3) on a plane
#       seen by a perspective and an orthographic camera at several resolutions and sensor fits:
#       the drivers' values against the pixel width computed here; prints SKINBAKE_FOOTPRINT
#       n_checked largest_relative_difference simple|python (the drivers' expression kind)
#   blender -b --factory-startup --python blender_scene.py -- mean A.exr
#       prints SKINBAKE_MEAN r g b, the mean of the whole image
#   blender -b --factory-startup --python blender_scene.py -- blocks A.exr B.exr K THR
#       mean (over blocks and RGB) and largest relative difference of A from B over K x K pixel
#       blocks that lie, with the pixels within 2 px of them, where B is brighter than THR times
#       its maximum; prints SKINBAKE_BLOCKS n mean max
import json
import math
import os
import subprocess
import sys

import bpy
from mathutils import Vector


def direction(elev, azim):
    e, a = math.radians(elev), math.radians(azim)
    return Vector((math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)))


def add_lamp(name, kind, energy, where):
    d = bpy.data.lights.new(name, kind)
    d.energy = energy
    if kind == "SUN":
        d.angle = 0.0
    else:
        d.shadow_soft_size = 0.0
    o = bpy.data.objects.new(name, d)
    bpy.context.scene.collection.objects.link(o)
    if kind == "SUN":
        o.rotation_euler = where.to_track_quat("Z", "Y").to_euler()
    else:
        o.location = where
    return o


def material(name, rgb):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = rgb + (1.0,)
    return m


def camera(loc, target, lens=50.0):
    cd = bpy.data.cameras.new("Camera")
    cd.lens = lens
    cam = bpy.data.objects.new("Camera", cd)
    bpy.context.scene.collection.objects.link(cam)
    cam.location = loc
    cam.rotation_euler = (Vector(target) - Vector(loc)).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.camera = cam
    return cam


def head():
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.1)
    o = bpy.context.active_object
    o.name = "Head"
    o.scale = (1.0, 0.85, 1.15)
    bpy.ops.object.transform_apply(scale=True)
    bpy.ops.object.shade_smooth()
    o.data.materials.append(material("HeadOld", (0.8, 0.6, 0.5)))
    return o


def world_colour(w, rgb):
    """The world's colour; Blender 5.0 makes new worlds with nodes (World.color unused), so the
    Background node's too."""
    w.color = rgb
    if w.use_nodes and w.node_tree and "Background" in w.node_tree.nodes:
        w.node_tree.nodes["Background"].inputs["Color"].default_value = tuple(rgb) + (1.0,)


def make_lights(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    sc.world = bpy.data.worlds.new("World")
    world_colour(sc.world, (0.0, 0.0, 0.0))
    head()
    camera((0.12, -0.38, 0.07), (0, 0, 0))
    add_lamp("Key", "SUN", 3.0, direction(40, -60))
    add_lamp("Rim", "SUN", 2.0, direction(25, 110))
    add_lamp("Fill", "POINT", 4.0, Vector((-0.35, -0.3, 0.05)))
    top = add_lamp("Top", "SPOT", 3.0, Vector((0.05, -0.2, 0.45)))
    top.data.spot_size, top.data.spot_blend = math.radians(100), 0.0    # the head is well inside
    top.rotation_euler = (-top.location).to_track_quat("-Z", "Y").to_euler()
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(out))


def snapshot():
    sc = bpy.context.scene
    s = {"objects": {}, "materials": sorted(m.name for m in bpy.data.materials if not m.name.startswith("skinbake")),
         "world": [sc.world.name, list(sc.world.color)], "camera": sc.camera.name, "prop": sc.get("my_prop"),
         "collections": {c.name: sorted(o.name for o in c.objects if o.type != "LIGHT")
                         for c in bpy.data.collections if not c.name.startswith("skinbake")}}
    for o in bpy.data.objects:
        e = {"type": o.type, "location": [round(x, 6) for x in o.matrix_world.translation],
             "hide_render": o.hide_render, "in_scene": o.name in sc.objects}
        if o.type == "MESH":
            e["materials"] = [s.material.name if s.material else None for s in o.material_slots]
        if o.type == "LIGHT":
            e["light"] = [o.data.type, round(o.data.energy, 6), list(o.data.color)]
        s["objects"][o.name] = e
    return s


def make_keep(out, snap):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    w = bpy.data.worlds.new("Sky")
    world_colour(w, (0.05, 0.06, 0.08))
    sc.world = w
    sc["my_prop"] = 42
    head()
    bpy.ops.mesh.primitive_cube_add(size=0.2, location=(0, 0, -0.25))
    body = bpy.context.active_object
    body.name = "Body"
    body.data.materials.append(material("BodyMat", (0.2, 0.3, 0.4)))
    bpy.ops.mesh.primitive_plane_add(size=2, location=(0, 0, -0.4))
    floor = bpy.context.active_object
    floor.name = "Floor"
    floor.data.materials.append(material("FloorMat", (0.5, 0.5, 0.5)))
    props = bpy.data.collections.new("Props")
    sc.collection.children.link(props)
    e = bpy.data.objects.new("Marker", None)
    props.objects.link(e)
    spare = material("Spare", (0.1, 0.9, 0.1))
    spare.use_fake_user = True
    camera((0.2, -0.8, 0.1), (0, 0, -0.1))
    add_lamp("Key", "SUN", 3.0, direction(40, -60))
    add_lamp("Panel", "AREA", 20.0, Vector((0.5, -0.5, 0.5)))
    add_lamp("Bulb", "POINT", 10.0, Vector((0.0, 0.5, 0.5))).hide_render = True
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(out))
    with open(snap, "w") as f:
        json.dump(snapshot(), f, indent=1, sort_keys=True)


def check_keep(snap):
    with open(snap) as f:
        old = json.load(f)
    new = snapshot()
    bad = []
    for k in ("materials", "world", "camera", "prop", "collections"):
        if old[k] != new[k]:
            bad.append(f"{k}: {old[k]} -> {new[k]}")
    for name, e in old["objects"].items():
        n = new["objects"].get(name)
        if n is None:
            bad.append(f"object {name} missing")
            continue
        for k, v in e.items():
            if name == "Head" and k == "materials":
                continue
            if n.get(k) != v:
                bad.append(f"object {name}.{k}: {v} -> {n.get(k)}")
    print("SKINBAKE_KEEP_OK" if not bad else "SKINBAKE_KEEP_DIFF " + "; ".join(bad))


def read(path):
    img = bpy.data.images.load(os.path.abspath(path), check_existing=False)
    img.colorspace_settings.name = "Non-Color"
    w, h, ch = img.size[0], img.size[1], img.channels
    px = list(img.pixels)
    bpy.data.images.remove(img)
    return w, h, [px[i:i + 3] for i in range(0, len(px), ch)]


def lamp_light(o, p):
    """(unit vector toward the lamp, irradiance on a surface facing it) at point p."""
    if o.data.type == "SUN":
        return (o.matrix_world.to_quaternion() @ Vector((0.0, 0.0, 1.0))).normalized(), o.data.energy
    d = o.matrix_world.translation - p
    r2 = d.length_squared
    e = o.data.energy / (4.0 * math.pi * r2)       # Cycles: radiant intensity P / 4 pi (measured)
    if o.data.type == "SPOT":                      # inside the cone (blend 0) a spot is a point lamp
        axis = o.matrix_world.to_quaternion() @ Vector((0.0, 0.0, -1.0))
        if o.data.spot_blend != 0 or math.acos(max(-1.0, min(1.0, axis.dot(-d.normalized())))) > o.data.spot_size / 2:
            raise SystemExit("blender_scene.py: only points inside a hard-edged spot cone are modelled")
    return d.normalized(), e


def measure_lights(helper, bake, stem, res, samples, exit_range=(0.0, 90.0), helper_args=()):
    sc = bpy.context.scene
    sc.render.resolution_x = sc.render.resolution_y = res
    sc.render.resolution_percentage = 100
    cy = sc.cycles
    cy.samples, cy.use_denoising, cy.use_adaptive_sampling, cy.seed = samples, False, False, 0
    layers = list(sc.get("skinbake_exact_layers", []))
    if layers:                         # exact mode: direct light only, the reference has no
        cy.max_bounces = 0             # interreflection
    else:                              # general mode: its subsurface walk needs the bounces
        layers = [v.name for v in sc.view_layers if v.use]
    cy.light_sampling_threshold = 0.0  # no roulette of dim light samples (it quantizes dim pixels)
    cy.filter_width = 0.01             # every sample at the pixel centre, as the passes
    sc.view_settings.view_transform = "Standard"
    vl = sc.view_layers[layers[0]]
    vl.use_pass_normal = vl.use_pass_position = True
    nt = sc.node_tree if hasattr(sc, "node_tree") else sc.compositing_node_group     # 5.0: a node group
    if nt is None and hasattr(sc, "node_tree"):     # general mode (up to 4.x): no compositor yet
        sc.use_nodes = True
        nt = sc.node_tree
    rl = nt.nodes.new("CompositorNodeRLayers")
    rl.layer = vl.name
    fo = nt.nodes.new("CompositorNodeOutputFile")
    directory = os.path.dirname(os.path.abspath(stem))
    if hasattr(fo.format, "media_type"):
        fo.format.media_type = "IMAGE"
    fo.format.file_format, fo.format.color_depth = "OPEN_EXR", "32"
    base = os.path.basename(stem)
    if hasattr(fo, "file_slots"):      # up to 4.x: one slot per file, frame number appended
        fo.base_path = directory
        fo.file_slots.clear()
        for p in ("Normal", "Position"):
            fo.file_slots.new(f"{base}_{p}_")
            nt.links.new(rl.outputs[p], fo.inputs[-1])
        pass_file = {p: f"{base}_{p}_{sc.frame_current:04d}.exr" for p in ("Normal", "Position")}
    else:                              # 5.0: items, files named FILE_NAME + item name
        fo.directory = directory
        fo.file_name = base + "_"
        for p in ("Normal", "Position"):
            fo.file_output_items.new("VECTOR", p)
            nt.links.new(rl.outputs[p], fo.inputs[p])
        pass_file = {p: f"{base}_{p}.exr" for p in ("Normal", "Position")}
    fmt = sc.render.image_settings
    fmt.file_format, fmt.color_depth, fmt.color_mode = "OPEN_EXR", "32", "RGB"
    sc.render.filepath = os.path.abspath(stem + ".exr")
    bpy.ops.render.render(write_still=True)
    w, h, col = read(stem + ".exr")
    _, _, nrm = read(os.path.join(directory, pass_file["Normal"]))
    _, _, pos = read(os.path.join(directory, pass_file["Position"]))
    cam = sc.camera.matrix_world.translation
    ortho = sc.camera.data.type == "ORTHO"
    # an orthographic camera's view direction (toward the camera) is the same at every pixel
    fwd = (sc.camera.matrix_world.to_quaternion() @ Vector((0.0, 0.0, 1.0))).normalized()
    lamps = [o for o in sc.objects if o.type == "LIGHT" and not o.hide_render]
    on = [Vector(n).length > 0.5 for n in nrm]
    jobs = []                          # (pixel, irradiance * cos_l, "ti to phi")
    for y in range(1, h - 1):
        for x in range(1, w - 1):
            i = y * w + x
            if not all(on[i + dy * w + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1)):
                continue               # silhouette pixels mix object and background
            n = Vector(nrm[i]).normalized()
            p = Vector(pos[i])
            v = fwd if ortho else (cam - p).normalized()
            cv = n.dot(v)
            lo, hi = exit_range
            if cv <= 0.02 or not lo <= math.degrees(math.acos(min(cv, 1.0))) <= hi:
                continue
            for o in lamps:
                lv, e = lamp_light(o, p)
                cl = n.dot(lv)
                if cl <= 0:
                    continue
                vp, lp = v - n * cv, lv - n * cl
                c = vp.normalized().dot(lp.normalized()) if vp.length > 1e-9 and lp.length > 1e-9 else 0.0
                ph = math.degrees(math.acos(max(-1.0, min(1.0, c))))
                jobs.append((i, e * cl, f"{math.degrees(math.acos(min(cl, 1.0)))} "
                                        f"{math.degrees(math.acos(min(cv, 1.0)))} {ph}"))
    r = subprocess.run([helper, bake, *helper_args], input="\n".join(j[2] for j in jobs) + "\n",
                       capture_output=True, text=True, check=True)
    vals = [[float(t) for t in line.split()] for line in r.stdout.splitlines()]
    ref = {}
    for (i, ecl, _), f in zip(jobs, vals):
        acc = ref.setdefault(i, [0.0, 0.0, 0.0])
        for c in range(3):
            acc[c] += ecl * f[c]
    top = max(sum(v) for v in ref.values())
    errs, s_got, s_ref = [], [0.0] * 3, [0.0] * 3
    for i, v in ref.items():
        if sum(v) < 0.02 * top:
            continue
        errs.append(max(abs(col[i][c] / v[c] - 1.0) for c in range(3)))
        for c in range(3):
            s_got[c] += col[i][c]
            s_ref[c] += v[c]
    errs.sort()
    n = len(errs)
    print(f"SKINBAKE_LIGHTS {n} {sum(errs) / n:.6f} {errs[int(0.95 * n)]:.6f} {errs[-1]:.6f}")
    print("SKINBAKE_RING " + " ".join(f"{g / r:.6f}" for g, r in zip(s_got, s_ref)))


def make_scene_json(path, out):
    """The spheres of scene.json PATH with Diffuse BSDFs, frame and scale as the importer's."""
    with open(path) as f:
        sc = json.load(f)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scale = sc["unit_mm"] / 1000.0
    for ob in sc["objects"]:
        if ob["shape"] != "sphere" or ob["material"] != "plain":
            raise SystemExit(f"blender_scene.py: object {ob['name']}: only plain spheres are built")
        m = ob["to_world"]
        c = [sum(m[i][k] * ob["center"][k] for k in range(3)) + m[i][3] for i in range(3)]
        bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, radius=ob["radius"] * ob["scale"] * scale,
                                             location=Vector((c[0], c[2], c[1])) * scale)
        bpy.ops.object.shade_smooth()
        o = bpy.context.active_object
        o.name = ob["name"]
        mt = bpy.data.materials.new(ob["name"])
        mt.use_nodes = True
        nt = mt.node_tree
        nt.nodes.remove(nt.nodes["Principled BSDF"])
        d = nt.nodes.new("ShaderNodeBsdfDiffuse")
        d.inputs["Color"].default_value = tuple(ob["color"]) + (1.0,)
        nt.links.new(d.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
        o.data.materials.append(mt)
    wd = bpy.data.worlds.new("World")
    scene.world = wd
    wd.color = (0.0, 0.0, 0.0)
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device, cy.samples, cy.use_denoising, cy.use_adaptive_sampling, cy.seed = "CPU", 4, False, False, 0
    cy.max_bounces = 0                 # direct light only: POV-Ray without radiosity
    cy.filter_width = 0.01             # samples at the pixel centre, as POV-Ray without antialiasing
    scene.view_settings.view_transform = "Standard"
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(out))


def _pixel_points(scene, w, h):
    """The surface point [Blender units] seen at each pixel centre (row 0 at the bottom, as
    read() gives pixels) by SCENE's camera, or None."""
    cam = scene.camera
    mw = cam.matrix_world
    tr, br, bl, tl = cam.data.view_frame(scene=scene)
    dg = bpy.context.evaluated_depsgraph_get()
    fwd = (mw.to_quaternion() @ Vector((0.0, 0.0, -1.0))).normalized()
    pts = []
    for y in range(h):
        for x in range(w):
            q = mw @ (bl + (br - bl) * ((x + 0.5) / w) + (tl - bl) * ((y + 0.5) / h))
            if cam.data.type == "ORTHO":
                o, d = q - fwd * 1e3 * (q - mw.translation).length, fwd
            else:
                o, d = mw.translation, (q - mw.translation).normalized()
            hit, loc = scene.ray_cast(dg, o, d)[:2]
            pts.append(loc.copy() if hit else None)
    return pts


def scene_compare(b, p, sjson):
    """B rendered from this file with SJSON's camera and lights against POV-Ray's P.  A point
    light of a scene file does not fade, Blender's falls off as 1/d^2 from its value at the
    look_at: with one point light (and no other) each pixel of pi B is scaled by d^2 / d_look^2,
    d the distance from the lamp to the surface point the camera sees there."""
    with open(sjson) as f:
        sc = json.load(f)
    w, h, pb = read(b)
    w2, h2, pp = read(p)
    if (w, h) != (w2, h2):
        raise SystemExit(f"{b} and {p} differ in size")
    pb = [[math.pi * v for v in px] for px in pb]
    if [L["type"] for L in sc["lights"]] == ["point"]:
        scale = sc["unit_mm"] / 1000.0

        def bl(v):
            return Vector((v[0], v[2], v[1])) * scale
        lamp, look = bl(sc["lights"][0]["position"]), bl(sc["camera"]["look_at"])
        pts = _pixel_points(bpy.context.scene, w, h)
        for i, q in enumerate(pts):
            if q is not None:
                f = (lamp - q).length_squared / (lamp - look).length_squared
                pb[i] = [v * f for v in pb[i]]
    top = max(max(sum(px) for px in pp), 1e-12)
    lit_b = [sum(px) > 0.02 * top for px in pb]
    lit_p = [sum(px) > 0.02 * top for px in pp]

    def centroid(lit):
        pts = [(i % w, i // w) for i in range(w * h) if lit[i]]
        return len(pts), sum(x for x, _ in pts) / max(len(pts), 1), sum(y for _, y in pts) / max(len(pts), 1)
    nb, xb, yb = centroid(lit_b)
    npv, xp, yp = centroid(lit_p)
    bad = sum(1 for i in range(w * h) if lit_b[i] != lit_p[i])
    print(f"SKINBAKE_SILHOUETTE {bad} {nb} {npv} {xb - xp:.3f} {yb - yp:.3f}")
    errs = []
    for by in range(0, h - 1, 2):
        for bx in range(0, w - 1, 2):
            ring = [y * w + x for y in range(max(by - 2, 0), min(by + 4, h)) for x in range(max(bx - 2, 0), min(bx + 4, w))]
            if not all(lit_b[i] and lit_p[i] for i in ring):
                continue
            idx = [(by + dy) * w + bx + dx for dy in range(2) for dx in range(2)]
            sb = [sum(pb[i][c] for i in idx) for c in range(3)]
            sp = [sum(pp[i][c] for i in idx) for c in range(3)]
            errs.append(max(abs(sb[c] / sp[c] - 1.0) for c in range(3) if sp[c] > 0))
    errs.sort()
    n = len(errs)
    print(f"SKINBAKE_SHADING {n} {sum(errs) / max(n, 1):.6f} {errs[int(0.9 * n)] if n else 1.0:.6f}")


def blocks(a, b, k, thr):
    w, h, pa = read(a)
    w2, h2, pb = read(b)
    if (w, h) != (w2, h2):
        raise SystemExit(f"{a} and {b} differ in size")
    lum = [sum(p) for p in pb]
    top = max(lum)
    errs = []
    for by in range(0, h - k + 1, k):
        for bx in range(0, w - k + 1, k):
            idx = [(by + dy) * w + bx + dx for dy in range(k) for dx in range(k)]
            ring = [(y * w + x) for y in range(max(by - 2, 0), min(by + k + 2, h))
                    for x in range(max(bx - 2, 0), min(bx + k + 2, w))]
            if min(lum[i] for i in ring) <= thr * top:
                continue               # background, or within 2 px of it: the pixel filters
                                       # (1.5 px wide) mix the silhouette in differently
            sa = [sum(pa[i][c] for i in idx) for c in range(3)]
            sb = [sum(pb[i][c] for i in idx) for c in range(3)]
            errs.append([abs(sa[c] / sb[c] - 1.0) for c in range(3)])
    n = len(errs)
    mean = sum(sum(e) for e in errs) / (3 * n)
    print(f"SKINBAKE_BLOCKS {n} {mean:.6f} {max(max(e) for e in errs):.6f}")



def footprint_check(importer):
    """footprint.py's drivers against the pixel width, for the cameras and resolutions below."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(importer)))
    sys.dont_write_bytecode = True
    from skinbake_import import footprint, nodes
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    cd = bpy.data.cameras.new("Camera")
    cam = bpy.data.objects.new("Camera", cd)
    sc.collection.objects.link(cam)
    sc.camera = cam
    bpy.ops.mesh.primitive_plane_add(size=0.2)
    mat = bpy.data.materials.new("fp")
    bpy.context.active_object.data.materials.append(mat)        # drivers evaluate in the depsgraph
    tr = nodes.Tree(mat)
    footprint.footprint(tr, sc, (0, 0))
    vals = {n.label: n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeValue"}
    per_m = vals["pixel width per unit distance (driver)"].outputs[0]
    ortho = vals["orthographic pixel width (driver)"].outputs[0]
    worst, n = 0.0, 0
    for ty, fit, rx, ry, pc in (("PERSP", "AUTO", 640, 480, 100), ("PERSP", "AUTO", 480, 640, 50),
                                ("PERSP", "HORIZONTAL", 300, 900, 100), ("PERSP", "VERTICAL", 640, 480, 25),
                                ("ORTHO", "AUTO", 64, 64, 100), ("ORTHO", "VERTICAL", 200, 100, 100)):
        cd.type, cd.sensor_fit, cd.lens, cd.sensor_width, cd.sensor_height = ty, fit, 35.0, 36.0, 24.0
        cd.ortho_scale = 0.23
        r = sc.render
        r.resolution_x, r.resolution_y, r.resolution_percentage = rx, ry, pc
        bpy.context.view_layer.update()
        side = {"AUTO": max(rx, ry), "HORIZONTAL": rx, "VERTICAL": ry}[fit] * pc / 100.0
        want = (0.0, 0.23 / side) if ty == "ORTHO" else \
            ((24.0 if fit == "VERTICAL" else 36.0) / 35.0 / side, 0.0)
        for got, w in zip((per_m.default_value, ortho.default_value), want):
            worst = max(worst, abs(got - w) / max(w, 1e-12) if w else abs(got))
            n += 1
        print("SKINBAKE_FOOTPRINT_CASE", ty, fit, rx, ry, pc, per_m.default_value, ortho.default_value, want)
    # Simple expressions run without Python, so they work in files whose scripts are not trusted.
    simple = all(fc.driver.is_simple_expression for fc in mat.node_tree.animation_data.drivers)
    print(f"SKINBAKE_FOOTPRINT {n} {worst:.2e} {'simple' if simple else 'python'}")

args = sys.argv[sys.argv.index("--") + 1:]
cmd = args[0]
if cmd == "make-lights":
    make_lights(args[1])
elif cmd == "material-summary":
    mt = bpy.data.materials[args[1]]
    nt = mt.node_tree
    imgs = sorted({n.image.name for n in nt.nodes if n.type == "TEX_IMAGE" and n.image is not None})
    bad = [n.image.name for n in nt.nodes if n.type == "TEX_IMAGE" and (n.image is None or not n.image.has_data
                                                                        and n.image.size[0] == 0)]
    print("SKINBAKE_VERSION", bpy.app.version_string.split()[0])
    print("SKINBAKE_MATERIAL", f"{len(nt.nodes)}_nodes_{len(nt.links)}_links_images_{'+'.join(imgs)}"
          + (f"_unreadable_{'+'.join(bad)}" if bad else ""))
    for n in nt.nodes:
        print("SKINBAKE_NODE", n.name.replace(" ", "_"), n.bl_idname)
elif cmd == "make-keep":
    make_keep(args[1], args[2])
elif cmd == "check-keep":
    check_keep(args[1])
elif cmd == "measure-lights":
    rng = [float(x) for x in args[6].split(":")] if len(args) > 6 else [0.0]
    measure_lights(os.path.abspath(args[1]), os.path.abspath(args[2]), args[3], int(args[4]),
                   int(args[5]), (rng[0], rng[1] if len(rng) > 1 else 90.0), args[7:])
elif cmd == "addon":
    sys.path.insert(0, os.path.dirname(os.path.abspath(args[1])))
    sys.dont_write_bytecode = True
    import import_skin
    import_skin.register()
    for o in bpy.context.view_layer.objects:
        o.select_set(o.name == args[3])
    r = bpy.ops.import_scene.skinbake(filepath=os.path.abspath(args[2]), mode="EXACT")
    sc = bpy.context.scene
    print("SKINBAKE_ADDON", ",".join(sorted(r)), bpy.data.objects[args[3]].active_material.name.replace(" ", "_"),
          len([v for v in sc.view_layers if v.name.startswith("skinbake:")]))
elif cmd == "make-scene-json":
    make_scene_json(args[1], args[2])
elif cmd == "scene-compare":
    scene_compare(args[1], args[2], args[3])
elif cmd == "footprint":
    footprint_check(args[1])
elif cmd == "mean":
    w, h, px = read(args[1])
    print("SKINBAKE_MEAN " + " ".join(f"{sum(p[c] for p in px) / len(px):.6f}" for c in range(3)))
elif cmd == "blocks":
    blocks(args[1], args[2], int(args[3]), float(args[4]))
else:
    raise SystemExit(f"blender_scene.py: unknown command {cmd}")
