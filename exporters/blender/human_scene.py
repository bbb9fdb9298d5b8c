# human_scene.py: a user's scene around Debian's MakeHuman model, for the importer to skin.
#
#   blender -b --factory-startup --python exporters/blender/human_scene.py -- OUT.blend \
#       [--model /usr/share/assimp/models/Collada/human.zae] [--size 640x480] [--samples 32]
#       [--shot head|cheek|showcase] [--world W]
#
# Imports the Collada model (a .zae is a zip holding the .dae and the eye texture; it is unpacked
# next to OUT.blend), smooths the body mesh "human-base", frames a close-up of the head (or of the
# left cheek) with a perspective camera, adds a key sun and a fill point lamp and saves OUT.blend;
# --shot showcase takes the view and light of scenes/showcase-head.scene instead (the POV-Ray demo's
# head: a warm key sun of its key's irradiance, colour and size, and its cool fill as the world,
# which Cycles occludes as POV-Ray's fill_occlusion does; --world is ignored)
# (Cycles CPU, denoiser off, Standard view transform, 8-bit PNG output).  The model (assimp's test
# data, BSD-3-clause, from MakeHuman) is metres, Z up after Blender's import, face toward -Y.
import math
import os
import sys
import zipfile

import bpy
from mathutils import Vector


# scenes/showcase-head.scene (POV-Ray millimetres, y up): camera, key light, fill.
SHOWCASE_EYE, SHOWCASE_TARGET = (200, 1580, -620), (0, 1545, -90)
SHOWCASE_KEY, SHOWCASE_KEY_RGB, SHOWCASE_KEY_AREA = (-700, 1950, -850), (1.3, 1.17, 1.0), 300
SHOWCASE_FILL = (0.12, 0.14, 0.19)


def pov(v):
    """POV-Ray (x, y, z) mm of the scene -> Blender (x, z, y) m after the Collada import."""
    return Vector((v[0] / 1000, v[2] / 1000, v[1] / 1000))


def main(argv):
    import argparse
    ap = argparse.ArgumentParser(prog="human_scene.py")
    ap.add_argument("out")
    ap.add_argument("--model", default="/usr/share/assimp/models/Collada/human.zae")
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--shot", choices=("head", "cheek", "showcase"), default="head")
    ap.add_argument("--world", type=float, default=0.0, help="uniform world radiance (default 0)")
    a = ap.parse_args(argv)
    out = os.path.abspath(a.out)
    w, h = (int(x) for x in a.size.lower().split("x"))
    dae = a.model
    if a.model.lower().endswith(".zae"):
        dest = os.path.join(os.path.dirname(out), "human_model")
        with zipfile.ZipFile(a.model) as z:
            z.extractall(dest)
        dae = next(os.path.join(dest, n) for n in z.namelist() if n.lower().endswith(".dae"))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.wm.collada_import(filepath=dae)
    sc = bpy.context.scene
    body = bpy.data.objects["human-base"]
    for o in sc.objects:
        if o.type == "MESH":
            for p in o.data.polygons:
                p.use_smooth = True
    sub = body.modifiers.new("smooth", "SUBSURF")          # 13k quads: smooth the silhouette
    sub.levels = sub.render_levels = 1

    cd = bpy.data.cameras.new("Camera")
    if a.shot == "showcase":
        cd.sensor_fit, cd.angle = "HORIZONTAL", math.radians(30)
        eye, target = pov(SHOWCASE_EYE), pov(SHOWCASE_TARGET)
    elif a.shot == "head":
        cd.lens, eye, target = 85.0, Vector((0.30, -0.80, 1.59)), Vector((0.0, -0.06, 1.535))
    else:
        target = Vector((0.035, -0.10, 1.525))               # left cheek below the eye
        cd.lens, eye = 85.0, target + 0.07 * Vector((0.45, -0.88, 0.15)).normalized()
    cd.clip_start = 0.01
    cam = bpy.data.objects.new("Camera", cd)
    sc.collection.objects.link(cam)
    cam.location = eye
    cam.rotation_euler = (target - eye).to_track_quat("-Z", "Y").to_euler()
    sc.camera = cam

    key = bpy.data.lights.new("Key", "SUN")
    key.energy, key.angle = 4.0, 0.0                       # irradiance [W/m^2]
    ko = bpy.data.objects.new("Key", key)
    sc.collection.objects.link(ko)
    world = (a.world, a.world, a.world)
    if a.shot == "showcase":
        lp, peak = pov(SHOWCASE_KEY), max(SHOWCASE_KEY_RGB)
        key.energy = math.pi * peak                        # a white Lambert facing it: the key colour
        key.color = tuple(c / peak for c in SHOWCASE_KEY_RGB)
        key.angle = 2 * math.atan(0.5 * SHOWCASE_KEY_AREA / 1000 / (lp - target).length)
        ko.rotation_euler = (target - lp).to_track_quat("-Z", "Y").to_euler()
        world = SHOWCASE_FILL
    else:
        ko.rotation_euler = Vector((-0.55, -0.75, 0.55)).normalized().to_track_quat("Z", "Y").to_euler()
        fill = bpy.data.lights.new("Fill", "POINT")
        fill.energy, fill.shadow_soft_size = 8.0, 0.0      # [W]: about 0.6 W/m^2 at the face
        fo = bpy.data.objects.new("Fill", fill)
        sc.collection.objects.link(fo)
        fo.location = (0.75, -0.65, 1.45)

    wd = bpy.data.worlds.new("World")
    wd.use_nodes = True
    wd.node_tree.nodes["Background"].inputs["Color"].default_value = tuple(world) + (1.0,)
    sc.world = wd
    sc.render.engine = "CYCLES"
    cy = sc.cycles
    cy.device, cy.samples, cy.use_denoising, cy.use_adaptive_sampling = "CPU", a.samples, False, False
    cy.seed = 0
    sc.render.resolution_x, sc.render.resolution_y, sc.render.resolution_percentage = w, h, 100
    sc.view_settings.view_transform = "Standard"
    sc.view_settings.look = "None"
    fmt = sc.render.image_settings
    fmt.file_format, fmt.color_mode, fmt.color_depth, fmt.compression = "PNG", "RGB", "8", 90
    bpy.ops.wm.save_as_mainfile(filepath=out)
    print(f"human_scene.py: saved {out} ({a.shot}, {w}x{h}, {a.samples} samples)")


main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
