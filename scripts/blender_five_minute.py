# blender_five_minute.py: the comparison for scripts/demo.sh's head (issue 24): what a Blender
# user makes in five minutes, rendered in the view and light of scenes/showcase-head.scene.
#
#   blender -b --factory-startup --python scripts/blender_five_minute.py -- OUT.png \
#       [--model /usr/share/assimp/models/Collada/human.zae] [--size 640x480] [--samples 64]
#       [--base R,G,B] [--closeup] [--shot showcase|key|back] [--save FILE.blend] [--eyes EYES.png]
#
# --shot key: the showcase's view and key alone (a black world, the camera seeing the scene's
# background colour, the key a sun of 0.5 degrees: the
# scene's key is a point), as POV-Ray renders scenes/showcase-key.scene; --shot back: the view and the one light of
# scenes/human-head-earglow.scene (behind the right ear), a black world.  That light is a POV-Ray
# point light of colour 4 without falloff; here a point light of zero size whose power, 4 pi^2 r^2
# x 4 W, gives the same irradiance at the ear (r = 207 mm; a white Lambert plane 1 m from a 4 pi^2 W
# point light renders 0.9994 in Cycles 3.4), falling off as 1/r^2 elsewhere.
# --closeup: the view and light of scenes/showcase-closeup.scene instead (25 mm of the left cheek;
# the key, a point light of colour 2.4 raking at about 65 degrees from the normal, as a sun of
# strength pi x 2.4 and angle 0.5 degrees; no fill, as that scene has none).  --save: also save the
# scene as FILE.blend before rendering, so that import_skin.py can put skinbake's material into the
# same view (scripts/closeup-compare.sh).
#
# The material: one Principled BSDF on the whole body, base and subsurface colour R,G,B (default
# the diffuse albedo at normal incidence of the demo's fair skin, from the export's Lambert
# stand-in), subsurface 1 with random walk, radius 3.67, 1.37, 0.68 mm, roughness 0.45, specular
# 0.5, no maps, no relief.  The eyes get the POV-Ray demo's eye material (eye_material below):
# --eyes EYES.png, the model's brown_eye.png recoloured by scripts/eye_texture.py (hazel irises,
# near-white sclerae; Blender's Python has no numpy, so the caller makes it, as
# scripts/gallery-showcase.sh does; without it the model's texture), its alpha linked to the
# Principled BSDF's (the model's material leaves it unlinked, so the corneas, which map to texels
# of alpha 0 and colour black, rendered the eyes black), roughness 0.15 for a wet highlight.
# The light: the showcase's key (a
# point light of colour 1.3 1.17 1.0 with a 300 mm area at 1.11 m, KEY below) as a sun of strength
# pi x 1.3 and that colour over 1.3, angle 15.4 degrees (a white Lambert surface facing it gives
# the key's colour in both renderers), and its fill (0.12 0.14 0.19) as a uniform world of that
# radiance (occluded, as POV-Ray's fill_occlusion makes it).  One level of subdivision, Cycles CPU, Standard view transform, sRGB 8-bit PNG.
# Coordinates: POV-Ray's (x, y, z) mm of the scene are Blender's (x, z, y) / 1000 after the
# Collada import (Z up, face toward -Y).
import math
import os
import sys
import tempfile
import zipfile

import bpy
from mathutils import Vector


# scenes/showcase-head.scene's camera, key and fill (POV-Ray millimetres).
EYE, TARGET = (200, 1580, -620), (0, 1545, -90)
KEY, KEY_RGB, KEY_AREA = (-700, 1950, -850), (1.3, 1.17, 1.0), 300
FILL = (0.12, 0.14, 0.19)
# scenes/human-head-earglow.scene's camera and light, and the right ear (scripts/showcase_masks.py).
BACK_EYE, BACK_TARGET = (650, 1600, -330), (20, 1565, 0)
BACK_LIGHT, BACK_RGB, BACK_EAR = (90, 1560, 200), 4.0, (80, 1535, -5)
KEY_BG, BACK_BG = (0.05, 0.05, 0.06), (0.02, 0.02, 0.025)   # the scenes' backgrounds


def pov(v):
    return Vector((v[0] / 1000, v[2] / 1000, v[1] / 1000))


def eye_material(png):
    """The demo's eyes: png (made by scripts/eye_texture.py), alpha used, wet surface."""
    m = bpy.data.materials.new("demo eyes")
    m.use_nodes = True
    nt = m.node_tree
    b = nt.nodes["Principled BSDF"]
    t = nt.nodes.new("ShaderNodeTexImage")
    t.image = bpy.data.images.load(os.path.abspath(png))
    t.interpolation = "Linear"
    nt.links.new(t.outputs["Color"], b.inputs["Base Color"])
    nt.links.new(t.outputs["Alpha"], b.inputs["Alpha"])
    b.inputs["Roughness"].default_value = 0.15
    b.inputs["Specular"].default_value = 0.5
    m.blend_method = "HASHED"
    return m


def main(argv):
    import argparse
    ap = argparse.ArgumentParser(prog="blender_five_minute.py")
    ap.add_argument("out")
    ap.add_argument("--model", default="/usr/share/assimp/models/Collada/human.zae")
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--samples", type=int, default=64)
    ap.add_argument("--base", default="0.4322,0.2283,0.2030")
    ap.add_argument("--closeup", action="store_true")
    ap.add_argument("--shot", choices=("showcase", "key", "back"), default="showcase")
    ap.add_argument("--save", default=None)
    ap.add_argument("--eyes", default=None)
    a = ap.parse_args(argv)
    w, h = (int(x) for x in a.size.lower().split("x"))
    base = tuple(float(x) for x in a.base.split(",")) + (1.0,)
    dae = a.model
    if dae.lower().endswith(".zae"):
        dest = tempfile.mkdtemp()
        with zipfile.ZipFile(dae) as z:
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
    sub = body.modifiers.new("smooth", "SUBSURF")
    sub.levels = sub.render_levels = 1

    m = bpy.data.materials.new("five-minute skin")
    m.use_nodes = True
    b = m.node_tree.nodes["Principled BSDF"]
    b.inputs["Base Color"].default_value = base
    b.inputs["Subsurface"].default_value = 1.0          # a multiplier of the radius too (3.x)
    b.inputs["Subsurface Radius"].default_value = (0.00367, 0.00137, 0.00068)
    b.inputs["Subsurface Color"].default_value = base
    b.subsurface_method = "RANDOM_WALK"
    b.inputs["Roughness"].default_value = 0.45
    b.inputs["Specular"].default_value = 0.5
    body.data.materials.clear()
    body.data.materials.append(m)
    eyes = next((o for o in sc.objects if o.type == "MESH" and "eyes" in o.name), None)
    eye_png = a.eyes or os.path.join(os.path.dirname(dae), "textures", "brown_eye.png")
    if not os.path.exists(eye_png):
        eye_png = None
    if eyes is not None and eye_png is not None:
        em = eye_material(eye_png)
        eyes.data.materials.clear()
        eyes.data.materials.append(em)

    cd = bpy.data.cameras.new("Camera")
    cd.sensor_fit = "HORIZONTAL"
    cd.angle = math.radians(20 if a.closeup else 30)
    cd.clip_start = 0.01
    cam = bpy.data.objects.new("Camera", cd)
    sc.collection.objects.link(cam)
    eye, target = pov(EYE), pov(TARGET)
    if a.closeup:
        eye, target = pov((-83, 1521, -187)), pov((-45, 1521, -128))
    elif a.shot == "back":
        eye, target = pov(BACK_EYE), pov(BACK_TARGET)
    cam.location = eye
    cam.rotation_euler = (target - eye).to_track_quat("-Z", "Y").to_euler()
    sc.camera = cam

    sun = bpy.data.lights.new("Key", "POINT" if a.shot == "back" else "SUN")
    if a.shot == "back":
        lp = pov(BACK_LIGHT)
        r = (lp - pov(BACK_EAR)).length
        sun.energy = 4 * math.pi ** 2 * r * r * BACK_RGB
        sun.shadow_soft_size = 0
    elif a.closeup:
        lp = pov((-313, 1745, -131))
        sun.energy = math.pi * 2.4
        sun.angle = math.radians(0.5)
    else:
        lp = pov(KEY)
        peak = max(KEY_RGB)
        sun.energy = math.pi * peak
        sun.color = tuple(c / peak for c in KEY_RGB)
        area = 0 if a.shot == "key" else KEY_AREA  # showcase-key.scene's key is a point
        sun.angle = max(2 * math.atan(0.5 * area / 1000 / (lp - target).length), math.radians(0.5))
    so = bpy.data.objects.new("Key", sun)
    sc.collection.objects.link(so)
    so.rotation_euler = (target - lp).to_track_quat("-Z", "Y").to_euler()
    so.location = lp

    world = bpy.data.worlds.new("fill")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    dark = a.closeup or a.shot != "showcase"
    bg.inputs["Color"].default_value = (0, 0, 0, 1) if dark else FILL + (1,)
    bg.inputs["Strength"].default_value = 1.0
    if a.shot != "showcase" and not a.closeup:
        # The scene's background seen by the camera only (POV-Ray's background lights nothing).
        nt = world.node_tree
        bgc = nt.nodes.new("ShaderNodeBackground")
        bgc.inputs["Color"].default_value = (BACK_BG if a.shot == "back" else KEY_BG) + (1,)
        lp_node = nt.nodes.new("ShaderNodeLightPath")
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(lp_node.outputs["Is Camera Ray"], mix.inputs["Fac"])
        nt.links.new(bg.outputs["Background"], mix.inputs[1])
        nt.links.new(bgc.outputs["Background"], mix.inputs[2])
        nt.links.new(mix.outputs["Shader"], nt.nodes["World Output"].inputs["Surface"])
    sc.world = world

    sc.render.engine = "CYCLES"
    sc.cycles.device = "CPU"
    sc.cycles.samples = a.samples
    sc.cycles.use_denoising = False
    sc.render.resolution_x, sc.render.resolution_y = w, h
    sc.render.resolution_percentage = 100
    sc.view_settings.view_transform = "Standard"
    sc.render.film_transparent = False
    sc.render.image_settings.file_format = "PNG"
    sc.render.filepath = os.path.abspath(a.out)
    if a.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(a.save))
    bpy.ops.render.render(write_still=True)
    print(f"blender_five_minute.py: wrote {a.out} ({w}x{h}, {a.samples} samples)")


main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
