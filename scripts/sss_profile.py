#!/usr/bin/env python3
"""Measure a renderer's own subsurface profile R(r) on a thick flat slab, in the real renderer.

  scripts/sss_profile.py pov    --colour R,G,B --radius T        [options] [--json OUT]
  scripts/sss_profile.py cycles --colour R,G,B --radius R,G,B    [options] [--json OUT]

Method (docs/translucency.md): the slab (much wider and thicker than the profile) is lit from
straight above by a parallel light of irradiance 1 everywhere except a disc of radius r around
the origin, which a black occluder a hair above the surface shadows (POV-Ray `no_image`, Cycles
camera-invisible).  A 180-degree equidistant fisheye camera just above the origin looks down, so
its cosine-weighted mean pixel is the exitance at the origin over all exit directions, which by
translation invariance is G(r) = 2 pi int_r^inf R(s) s ds.  One render per edge; a render with
no occluder gives G(0), the total.  Ring powers are differences of G; R(r) on a ring is its power
over its area.  The closure's own surface reflection is off (POV-Ray: specular 0; Cycles: the
Subsurface Scattering node alone).

Units: lengths in mm; irradiance 1, so ring powers and the integral are fractions of the
incident power.  Pixels are linear (POV-Ray File_Gamma 1, Cycles EXR with the Standard view);
a POV-Ray pixel is pi x radiance, a Cycles pixel radiance, so both are scaled to pi x radiance.

--back lights the slab's bottom face instead (edges 0 only): G(0) is the transmittance of a slab
of thickness --depth, over all exit directions.  --entry FILE (Cycles) renders the importer's own
nodes of a translucent set's versions[] entry with a "thickness" weight (translucent.py's
thickness_shader: the node weighted per channel by the local thickness) instead of one node.

pov:    finish { subsurface { translucency T } } with pigment COLOUR (the Rd POV-Ray aims at),
        global_settings { mm_per_unit 1 subsurface { samples N, 1 } }, interior { ior IOR }.
cycles: the Subsurface Scattering node (falloff --method: random_walk, random_walk_fixed,
        random_walk_skin on 4.x), colour COLOUR, scale 1, radius R,G,B mm, IOR, 1 unit = 1 mm.

The JSON holds the renderer and version, the parameters, the edges [mm], G at each edge, the
ring powers and R(r) [1/mm^2] per channel, the integral (to the last edge) and the mean radius
(power-weighted ring centroid) per channel.  Run inside Blender (`blender -b --python THIS -- ...`)
the cycles part renders; run outside, it starts Blender itself.
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

HERE_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FAR_ANGLES = [0.0, 20.0, 40.0, 60.0, 75.0, 85.0]       # theta_i and theta_o nodes of --far [deg]
DEFAULT_EDGES = [0.0, 0.02, 0.035, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.45, 0.65, 1.0, 1.5, 2.2,
                 3.2, 4.6, 6.5, 9.0, 13.0, 20.0]


def fisheye_weights(n):
    """Per pixel of an n x n 180-degree equidistant fisheye (theta = rho pi / 2 at pixel centres):
    cos(theta) d(omega), normalised to sum 1 (None outside the image circle)."""
    w = []
    for y in range(n):
        for x in range(n):
            u = 2.0 * ((x + 0.5) / n - 0.5)
            v = 2.0 * ((y + 0.5) / n - 0.5)
            rho = math.hypot(u, v)
            if rho >= 1.0:
                w.append(0.0)
                continue
            th = rho * math.pi / 2
            # d(omega) = sin(theta) d(theta) d(phi) = sin(theta) (pi/2) / rho dA
            w.append(math.cos(th) * math.sin(th) * (math.pi / 2) / rho)
    s = sum(w)
    return [x / s for x in w]


def weighted_mean(pixels, n, scale):
    """Cosine-weighted mean of pixels ([n*n][3], row-major) times SCALE per channel."""
    w = fisheye_weights(n)
    return [scale * sum(wi * p[c] for wi, p in zip(w, pixels)) for c in range(3)]


def profile(edges, g):
    """Rings from G at the edges (g[k][c]); the last ring ends at the last edge."""
    rings, rd, centroid = [], [], []
    for k in range(len(edges) - 1):
        r1, r2 = edges[k], edges[k + 1]
        p = [g[k][c] - g[k + 1][c] for c in range(3)]
        area = math.pi * (r2 * r2 - r1 * r1)
        rings.append(p)
        rd.append([x / area for x in p])
        centroid.append(2.0 / 3.0 * (r2 ** 3 - r1 ** 3) / (r2 * r2 - r1 * r1))
    integral = [sum(r[c] for r in rings) for c in range(3)]
    mean = [sum(r[c] * m for r, m in zip(rings, centroid)) / integral[c] if integral[c] > 0 else 0.0
            for c in range(3)]
    return {"ring_power": rings, "rd_per_mm2": rd, "ring_centroid_mm": centroid,
            "integral": integral, "mean_radius_mm": mean, "beyond_last_edge": g[-1]}


# ---------------------------------------------------------------- POV-Ray

POV_SCENE = """#version 3.7;
global_settings {{ assumed_gamma 1 ambient_light 0 mm_per_unit 1 subsurface {{ samples {samples}, 1 }} }}
camera {{ fisheye angle 180 location <0, {h}, 0> look_at <0, 0, 0> sky z right x up y }}
light_source {{ <0, {ly}, 0> rgb 1 parallel point_at <0, {lt}, 0> }}
{occluder}
box {{ <-{w}, -{d}, -{w}>, <{w}, 0, {w}>
  texture {{ pigment {{ rgb <{c[0]}, {c[1]}, {c[2]}> }}
    finish {{ diffuse 1 ambient 0 emission 0 specular 0 phong 0 subsurface {{ translucency <{t[0]}, {t[1]}, {t[2]}> }} }} }}
  {local}
  interior {{ ior {ior} }} }}
"""
# --local: the exporter's layering (export/pov/povsss.h): a Lambertian of albedo L over the
# subsurface layer, which then shows with weight 0.999.
POV_LOCAL = ("texture {{ pigment {{ average pigment_map {{ [1 rgb <{l[0]}, {l[1]}, {l[2]}>] [999 rgbt <0, 0, 0, 1>] }} }} "
             "finish {{ diffuse 1e6 ambient 0 emission 0 specular 0 phong 0 }} }}")


def read_ppm(path):
    d = open(path, "rb").read()
    toks, i = [], 2
    tok = re.compile(rb"\s*(?:#[^\n]*\n\s*)*(\d+)")
    while len(toks) < 3:
        m = tok.match(d, i)
        toks.append(int(m.group(1)))
        i = m.end()
    w, h, mx = toks
    i += 1
    nb = 2 if mx > 255 else 1
    raw = d[i:i + w * h * 3 * nb]
    vals = [int.from_bytes(raw[k:k + nb], "big") / mx for k in range(0, len(raw), nb)]
    return w, [vals[k:k + 3] for k in range(0, len(vals), 3)]


POV_FAR = """#version 3.7;
global_settings {{ assumed_gamma 1 ambient_light 0 mm_per_unit 1 subsurface {{ samples {samples}, 1 }} }}
camera {{ orthographic location {cam} look_at <0, 0, 0> sky y right x * 2 up y * 2 }}
light_source {{ {lig} rgb 1 parallel point_at <0, 0, 0> }}
box {{ <-{w}, -{d}, -{w}>, <{w}, 0, {w}>
  texture {{ pigment {{ rgb <{c[0]}, {c[1]}, {c[2]}> }}
    finish {{ diffuse 1 ambient 0 emission 0 specular 0 phong 0 subsurface {{ translucency <{t[0]}, {t[1]}, {t[2]}> }} }} }}
  interior {{ ior {ior} }} }}
"""


def far_dirs(ti, to):
    """Light and view directions (y up): light in the x-y plane at theta_i, view in the y-z plane
    at theta_o (delta_phi = 90 degrees, the mean of the azimuths)."""
    li = (math.sin(ti), math.cos(ti), 0.0)
    vo = (0.0, math.cos(to), math.sin(to))
    return li, vo


def pov_far(a):
    """pi f of the closure (fully lit slab, parallel light at theta_i, orthographic view at
    theta_o): mean pixel / cos(theta_i), per pair of FAR_ANGLES.  32 x 32 pixels: POV-Ray 3.7.0
    takes one subsurface sample per pixel whatever `samples` says (16 to 3200 gave the same
    image), its quasi-random sequence running on over the pixels, so the image mean is the
    estimate."""
    t = a.radius if len(a.radius) == 3 else a.radius * 3
    far = []
    with tempfile.TemporaryDirectory() as tmp:
        for ti in FAR_ANGLES:
            for to in FAR_ANGLES:
                li, vo = far_dirs(math.radians(ti), math.radians(to))
                src = POV_FAR.format(samples=a.samples, cam="<%g,%g,%g>" % tuple(100 * x for x in vo),
                                     lig="<%g,%g,%g>" % tuple(1000 * x for x in li), w=a.width, d=a.depth,
                                     c=a.colour, t=t, ior=a.ior)
                pov, ppm = os.path.join(tmp, "f.pov"), os.path.join(tmp, "f.ppm")
                with open(pov, "w") as f:
                    f.write(src)
                res = subprocess.run(["povray", "-D", "-A", "+W32", "+H32", "+FP16", "File_Gamma=1.0", "+WT2",
                                      f"+I{pov}", f"+O{ppm}"], capture_output=True, text=True)
                if res.returncode != 0 or not os.path.exists(ppm):
                    sys.exit(f"sss_profile: povray failed:\n{res.stderr[-2000:]}")
                n, px = read_ppm(ppm)
                far.append([sum(p[c] for p in px) / len(px) / li[1] for c in range(3)])
    return far


def pov_version():
    out = subprocess.run(["povray", "--version"], capture_output=True, text=True)
    m = re.search(r"POV-Ray (\S+)", out.stdout + out.stderr)
    return m.group(1) if m else "unknown"


def pov_measure(a):
    t = a.radius if len(a.radius) == 3 else a.radius * 3
    g = []
    with tempfile.TemporaryDirectory() as tmp:
        for r in a.edges:
            occ = "" if r <= 0 else (f"disc {{ <0, {max(3 * a.height, 0.01)}, 0>, y, {r} no_image pigment {{ rgb 0 }} "
                                     "finish { diffuse 0 ambient 0 } }")
            src = POV_SCENE.format(samples=a.samples, h=a.height, occluder=occ, w=a.width, d=a.depth,
                                   c=a.colour, t=t, ior=a.ior, ly=-1000 if a.back else 1000, lt=-a.depth if a.back else 0,
                                   local=POV_LOCAL.format(l=a.local) if a.local else "")
            pov, ppm = os.path.join(tmp, "p.pov"), os.path.join(tmp, "p.ppm")
            with open(pov, "w") as f:
                f.write(src)
            res = subprocess.run(["povray", "-D", "-A", f"+W{a.size}", f"+H{a.size}", "+FP16", "File_Gamma=1.0",
                                  "+WT2", f"+I{pov}", f"+O{ppm}"], capture_output=True, text=True)
            if res.returncode != 0 or not os.path.exists(ppm):
                sys.exit(f"sss_profile: povray failed:\n{res.stderr[-2000:]}")
            n, px = read_ppm(ppm)
            g.append(weighted_mean(px, n, 1.0))
            os.unlink(ppm)
    return {"renderer": "povray", "version": pov_version(), "closure": "subsurface translucency",
            "params": {"colour": a.colour, "translucency_mm": t, "ior": a.ior, "samples": a.samples,
                       "size": a.size, "mm_per_unit": 1}, "g": g}


# ---------------------------------------------------------------- Cycles

CYCLES_FALLOFF = {"random_walk": "RANDOM_WALK", "random_walk_fixed": "RANDOM_WALK_FIXED_RADIUS",
                  "random_walk_skin": "RANDOM_WALK_SKIN", "burley": "BURLEY"}


def _cycles_settings(sc, a):
    sc.render.engine = "CYCLES"
    sc.cycles.samples = a.samples
    sc.cycles.use_denoising = False
    sc.cycles.max_bounces = 64
    sc.cycles.device = "CPU"
    sc.render.threads_mode = "FIXED"
    sc.render.threads = 2
    sc.render.resolution_x = sc.render.resolution_y = a.size
    sc.render.resolution_percentage = 100
    sc.view_settings.view_transform = "Standard"
    sc.view_settings.look = "None"
    sc.view_settings.exposure = 0.0
    sc.view_settings.gamma = 1.0
    sc.render.image_settings.file_format = "OPEN_EXR"
    sc.render.image_settings.color_depth = "32"
    sc.render.image_settings.color_mode = "RGB"


def _cycles_material(a):
    """The slab's material: the Subsurface Scattering node alone (or, as a check of the
    measurement, a Diffuse BSDF, whose G(0) must equal its colour)."""
    import bpy
    mat = bpy.data.materials.new("sss")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    if a.entry:                                 # the importer's thickness-weighted nodes
        sys.path.insert(0, os.path.join(HERE_ROOT, "exporters", "blender"))
        from skinbake_import.translucent import check_thickness, thickness_shader
        with open(a.entry) as f:
            v = json.load(f)
        check_thickness(v["thickness"], a.entry)
        sock = thickness_shader(nt, v, FAR_ANGLES, 1e-3, (0, 0))
        nt.links.new(sock, out.inputs["Surface"])
        return mat
    if a.method == "diffuse":
        node = nt.nodes.new("ShaderNodeBsdfDiffuse")
    else:
        node = nt.nodes.new("ShaderNodeSubsurfaceScattering")
        if CYCLES_FALLOFF[a.method] not in [i.identifier for i in node.bl_rna.properties["falloff"].enum_items]:
            sys.exit(f"sss_profile: Blender {bpy.app.version_string} has no {a.method} subsurface")
        node.falloff = CYCLES_FALLOFF[a.method]
        node.inputs["Scale"].default_value = 1.0
        node.inputs["Radius"].default_value = a.radius if len(a.radius) == 3 else a.radius * 3
        if "IOR" in node.inputs:
            node.inputs["IOR"].default_value = a.ior
    node.inputs["Color"].default_value = (*a.colour, 1.0)
    if a.weight != 1.0:                         # the closure times WEIGHT: Mix Shader with nothing
        mix = nt.nodes.new("ShaderNodeMixShader")
        mix.inputs["Fac"].default_value = a.weight
        nt.links.new(node.outputs[0], mix.inputs[2])
        node = mix
    if a.local:                                 # the remainder's local part: a Lambertian beside it
        dif = nt.nodes.new("ShaderNodeBsdfDiffuse")
        dif.inputs["Color"].default_value = (*a.local, 1.0)
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(node.outputs[0], add.inputs[0])
        nt.links.new(dif.outputs[0], add.inputs[1])
        node = add
    nt.links.new(node.outputs[0], out.inputs["Surface"])
    return mat


def _cycles_scene(a):
    """Slab (top at z = 0), sun straight down of irradiance 1, occluder disc, fisheye camera."""
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    _cycles_settings(sc, a)
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    sc.world = world
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0, 0, -a.depth / 2))
    slab = bpy.context.object
    slab.scale = (2 * a.width, 2 * a.width, a.depth)
    slab.data.materials.append(_cycles_material(a))
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 1.0
    sun.angle = 0.0
    sob = bpy.data.objects.new("sun", sun)
    if a.back:                                  # shining up at the slab's bottom face
        sob.rotation_euler = (math.pi, 0.0, 0.0)
    sc.collection.objects.link(sob)
    bpy.ops.mesh.primitive_circle_add(vertices=256, radius=1.0, fill_type="NGON", location=(0, 0, 3 * a.height))
    occ = bpy.context.object
    omat = bpy.data.materials.new("black")
    omat.use_nodes = True
    omat.node_tree.nodes.clear()
    oout = omat.node_tree.nodes.new("ShaderNodeOutputMaterial")
    hold = omat.node_tree.nodes.new("ShaderNodeBsdfDiffuse")
    hold.inputs["Color"].default_value = (0, 0, 0, 1)
    omat.node_tree.links.new(hold.outputs[0], oout.inputs["Surface"])
    occ.data.materials.append(omat)
    occ.visible_camera = False
    cam = bpy.data.cameras.new("fisheye")
    cam.type = "PANO"
    pano = cam if hasattr(cam, "panorama_type") else cam.cycles     # 4.x / 3.x
    pano.panorama_type = "FISHEYE_EQUIDISTANT"
    pano.fisheye_fov = math.pi
    cam.clip_start = a.height / 10
    cob = bpy.data.objects.new("fisheye", cam)
    cob.location = (0, 0, a.height)
    sc.collection.objects.link(cob)
    sc.camera = cob
    return sc, occ


def cycles_inner(a):
    """Inside Blender: one fisheye render per edge; G per edge."""
    import bpy
    sc, occ = _cycles_scene(a)
    g = []
    with tempfile.TemporaryDirectory() as tmp:
        for k, r in enumerate(a.edges):
            occ.hide_render = r <= 0
            occ.scale = (max(r, 1e-6), max(r, 1e-6), 1.0)
            path = os.path.join(tmp, f"g{k}.exr")
            sc.render.filepath = path
            bpy.ops.render.render(write_still=True)
            img = bpy.data.images.load(path, check_existing=False)
            img.colorspace_settings.name = "Non-Color"
            n = img.size[0]
            flat = list(img.pixels)
            bpy.data.images.remove(img)
            # rows run bottom to top; the weights are symmetric, so the order does not matter
            g.append(weighted_mean([flat[4 * i:4 * i + 3] for i in range(n * n)], n, math.pi))
    rad = a.radius if len(a.radius) == 3 else a.radius * 3
    far = cycles_far(a, sc, occ) if a.far else None
    return {"far_pi_f": far, "renderer": "cycles", "version": bpy.app.version_string,
            "closure": "Subsurface Scattering node, falloff " + a.method,
            "params": {"colour": a.colour, "radius_mm": rad, "scale": 1.0, "weight": a.weight,
                       "ior": a.ior, "samples": a.samples,
                       "size": a.size}, "g": g}


def cycles_far(a, sc, occ):
    """pi f of the closure: fully lit slab, sun at theta_i, orthographic camera at theta_o."""
    import bpy
    from mathutils import Vector
    occ.hide_render = True
    cam = sc.camera
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = 2.0
    cam.data.clip_start = 0.1
    sc.render.resolution_x = sc.render.resolution_y = a.far_size
    sun = bpy.data.objects["sun"]
    far = []
    with tempfile.TemporaryDirectory() as tmp:
        for ti in (FAR_ANGLES if a.far_all else FAR_ANGLES[:1]):
            for to in FAR_ANGLES:
                li, vo = far_dirs(math.radians(ti), math.radians(to))
                # y up in far_dirs, z up here
                light, view = Vector((li[0], li[2], li[1])), Vector((vo[0], vo[2], vo[1]))
                sun.rotation_euler = light.to_track_quat("Z", "Y").to_euler()
                cam.location = 100.0 * view
                cam.rotation_euler = view.to_track_quat("Z", "Y").to_euler()
                path = os.path.join(tmp, "f.exr")
                sc.render.filepath = path
                bpy.ops.render.render(write_still=True)
                img = bpy.data.images.load(path, check_existing=False)
                img.colorspace_settings.name = "Non-Color"
                flat = list(img.pixels)
                bpy.data.images.remove(img)
                n = len(flat) // 4
                far.append([math.pi * sum(flat[4 * i + c] for i in range(n)) / n / li[1] for c in range(3)])
    return far


def cycles_measure(a, argv):
    blender = os.environ.get("BLENDER", "blender")
    res = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                          os.path.abspath(__file__), "--"] + argv + ["--inner"], capture_output=True, text=True)
    m = re.search(r"^SSS_PROFILE (.*)$", res.stdout, re.M)
    if res.returncode != 0 or not m:
        sys.exit(f"sss_profile: blender failed:\n{res.stdout[-1500:]}\n{res.stderr[-1500:]}")
    return json.loads(m.group(1))


# ---------------------------------------------------------------- CLI

def numbers(s):
    return [float(x) for x in s.split(",")]


def parse(argv):
    import argparse
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("renderer", choices=["pov", "cycles"])
    p.add_argument("--colour", type=numbers, required=True, help="R,G,B: POV-Ray pigment / Cycles colour")
    p.add_argument("--radius", type=numbers, required=True, help="POV-Ray translucency / Cycles radius [mm]")
    p.add_argument("--local", type=numbers, default=None, help="R,G,B: add a Lambertian of this albedo, the "
                   "part of the power the fit leaves to the table at the entry point (sss_fit.h: local)")
    p.add_argument("--weight", type=float, default=1.0, help="Cycles: the closure's weight in the "
                   "material (a Mix Shader with nothing; sss_fit.h: scale)")
    p.add_argument("--method", default="random_walk", help="Cycles falloff (random_walk, random_walk_fixed, "
                   "random_walk_skin, burley)")
    p.add_argument("--entry", help="Cycles: render the translucent set's node weighted by the "
                   "thickness (a versions[] entry of the manifest with \"thickness\", as JSON; "
                   "--colour and --radius are then only recorded)")
    p.add_argument("--ior", type=float, default=1.4)
    p.add_argument("--samples", type=int, default=None, help="POV-Ray diffuse samples / Cycles samples per pixel")
    p.add_argument("--size", type=int, default=32, help="fisheye image size [px]")
    p.add_argument("--edges", type=numbers, default=DEFAULT_EDGES, help="ring edges [mm], ascending from 0")
    # Cycles intersects in single precision: a camera 1e-4 mm above a slab 1 m wide loses most
    # of the subsurface light (measured: 0.165 of colour 0.5), 1e-3 mm above 60 mm is right.
    p.add_argument("--height", type=float, default=None, help="camera height [mm] (POV-Ray 1e-4, Cycles 1e-3)")
    p.add_argument("--width", type=float, default=None, help="slab half-width [mm] (POV-Ray 500, Cycles 30)")
    p.add_argument("--depth", type=float, default=None, help="slab thickness [mm] (POV-Ray 500, Cycles 30)")
    p.add_argument("--back", action="store_true", help="light the slab from below (its thickness --depth): "
                   "G(0) is then the diffuse transmittance over all exit directions")
    p.add_argument("--far", action="store_true", help="also the closure's far-field pi f(theta_i, theta_o) "
                   "at FAR_ANGLES (fully lit slab, orthographic camera)")
    p.add_argument("--far-theta-i-0", dest="far_all", action="store_false",
                   help="Cycles --far: light at theta_i = 0 only, one row of theta_o (the skin "
                   "walk of 4.x enters Lambertian: its far field does not depend on theta_i)")
    p.add_argument("--far-size", type=int, default=8, help="Cycles --far: image size [px]")
    p.add_argument("--json", help="write the result here (default stdout)")
    p.add_argument("--inner", action="store_true", help=argparse.SUPPRESS)
    a = p.parse_args(argv)
    if len(a.colour) != 3 or len(a.radius) not in (1, 3) or (a.local and len(a.local) != 3):
        p.error("--colour and --local take R,G,B and --radius one or three numbers")
    if a.edges[0] != 0.0 or any(y <= x for x, y in zip(a.edges, a.edges[1:])):
        p.error("--edges must start at 0 and ascend")
    pov = a.renderer == "pov"
    if a.samples is None:
        a.samples = 400 if pov else 256
    if a.height is None:
        a.height = 1e-4 if pov else 1e-3
    if a.width is None:
        a.width = 500.0 if pov else 30.0
    if a.depth is None:
        a.depth = 500.0 if pov else 30.0
    return a


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    a = parse(argv)
    argv = argv + [f"--height={a.height}", f"--width={a.width}", f"--depth={a.depth}", f"--samples={a.samples}"]
    if a.inner:
        print("SSS_PROFILE " + json.dumps(cycles_inner(a)))
        return
    r = pov_measure(a) if a.renderer == "pov" else cycles_measure(a, argv)
    r["edges_mm"] = a.edges
    r.update(profile(a.edges, r["g"]))
    if a.far:
        r["far_angles_deg"] = FAR_ANGLES
        r["far_pi_f"] = pov_far(a) if a.renderer == "pov" else r.pop("far_pi_f")
    text = json.dumps(r, indent=1)
    if a.json:
        with open(a.json, "w") as f:
            f.write(text + "\n")
    else:
        print(text)


if __name__ == "__main__":
    main()
