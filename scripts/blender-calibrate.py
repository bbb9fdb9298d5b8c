# Measure the general mode's calibration constants of this Blender (skinbake_import/calibration.py):
#   blender -b --factory-startup --python-exit-code 1 --python scripts/blender-calibrate.py -- [furnace|view] [SAMPLES]
#   (or, for bpy in a venv: PYTHON tests/bpy_blender.py --python scripts/blender-calibrate.py -- ...)
# furnace (the default): renders a closed box of Principled BSDF (random-walk subsurface, weight 1,
# radius 3.6 mm in all channels, specular 0) in a white furnace (world 1, no lamp), camera along the
# normal, for Base Colours 0.05 ... 0.95 at roughness 0 and 1, and prints the rendered / requested
# albedo as a Python dict entry to paste into calibration.MEASURED.  About 2 minutes at 256 samples.
# view (Blender 4+): the same closure (calibration.VIEW_IOR, roughness 0.02) on a wide closed box under
# a sun along the normal, black world, seen at the cosines VIEW_COS, for the Base Colours VIEW_BASE:
# pi L / E per Base Colour, the closure's response R(base, cos_view), printed as an entry for
# calibration.VIEW_RESPONSE; and the same at a sun 60 deg off the normal, which 4.x and 5.x render
# alike (cosine law: the light direction does not matter).  About 5 minutes at 128 samples.
# check (Blender 4+, tests/blender_lights.sh): Base Colours 0.02, 0.1, 0.45 at cos_view 0.45 with the
# sun 60 deg off the normal, and along the normal with the sun along it, against this Blender's
# VIEW_RESPONSE: prints SKINBAKE_VIEW_CHECK and the largest relative difference.  About 20 s.
# pixel: the subsurface radius, in pixel widths, below which this Blender renders the closure as a
# Lambert diffuse (Cycles 4.3: a quarter pixel): a wide box, orthographic camera along the normal,
# 24 px, Base Colour 0.3 under a sun along the normal, radii PIXEL_FRACTIONS pixels per channel; a
# channel rendered as diffuse gives pi L / E = 0.3 exactly and noiseless pixels, the walk
# 0.25 (4.x) or about 0.3 (3.4) with sampling noise.  Prints SKINBAKE_PIXEL
# with the largest fraction rendered as diffuse (0: none), the smallest rendered as the walk, and
# calibration.SSS_DIFFUSE_BELOW's value for this Blender.  About 10 s.
import math
import os
import sys
import tempfile

import bpy

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "exporters", "blender"))
from skinbake_import import calibration, nodes, scene  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
what = args.pop(0) if args and args[0] in ("furnace", "view", "check", "pixel") else "furnace"
samples = int(args[0]) if args else (256 if what == "furnace" else 128)
ALBEDO = (0.05, 0.15, 0.3, 0.6, 0.8, 0.95)
VIEW_COS = (0.1, 0.2, 0.3, 0.45, 0.6, 0.75, 0.9, 1.0)
PIXEL_FRACTIONS = (0.01, 0.1, 0.24, 0.26, 0.5, 1.0)
VIEW_BASE = (0.005, 0.01, 0.02, 0.035, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0, 0.25)


def principled(ob, colour, roughness, ior=None, radius=(3.6e-3,) * 3):
    mat = bpy.data.materials.new("calibrate")
    tr = nodes.Tree(mat)
    out = tr.node("ShaderNodeOutputMaterial", (400, 0))
    b = tr.node("ShaderNodeBsdfPrincipled", (0, 0))
    b.subsurface_method = "RANDOM_WALK"
    b.inputs["Base Color"].default_value = list(colour) + [1.0]
    if nodes.sock(b.inputs, "Subsurface Color"):
        nodes.sock(b.inputs, "Subsurface Color").default_value = list(colour) + [1.0]
    nodes.sock(b.inputs, "Subsurface Weight", "Subsurface").default_value = 1.0
    if nodes.sock(b.inputs, "Subsurface Scale"):
        nodes.sock(b.inputs, "Subsurface Scale").default_value = 1.0
    b.inputs["Subsurface Radius"].default_value = radius
    nodes.sock(b.inputs, "Specular", "Specular IOR Level").default_value = 0.0
    b.inputs["Roughness"].default_value = roughness
    if ior is not None:
        b.inputs["IOR"].default_value = ior
    tr.link(b.outputs["BSDF"], out.inputs["Surface"])
    ob.data.materials.append(mat)


def furnace(colour, roughness, tmp):
    sc, ob = scene.build_scene({"exact": {"sun_direction": [0, 0, 1]}}, "box", 64, samples, 1.0, 0.0, (90, 0))
    principled(ob, colour, roughness)
    return scene.render(sc, os.path.join(tmp, "f.exr"))


def lit(colour, cos_view, sun_deg, tmp, radius=(3.6e-3,) * 3):
    """pi L / E of the closure of Base COLOUR seen at COS_VIEW, the sun SUN_DEG off the normal."""
    t = math.radians(sun_deg)
    sun = [math.sin(t), 0.0, math.cos(t)]
    elev = math.degrees(math.asin(cos_view))
    sc, ob = scene.build_scene({"exact": {"sun_direction": sun}}, "box", 24, samples, 0.0, 1.0, (elev, 0))
    ob.scale = (5.0, 5.0, 1.0)            # 1 m wide: a 0.02 m window seen at cos 0.1 stays far from the edges
    sc.camera.data.ortho_scale = 0.02
    principled(ob, colour, calibration.VIEW_ROUGHNESS, calibration.VIEW_IOR, radius)
    path = os.path.join(tmp, "v.exr")
    scene.render(sc, path)
    img = bpy.data.images.load(path, check_existing=False)
    img.colorspace_settings.name = "Non-Color"
    px, ch = list(img.pixels), img.channels
    n = len(px) // ch
    mean = [sum(px[i * ch + c] for i in range(n)) / n for c in range(3)]
    # The pixels' spread per channel relative to the mean: 0 for a Lambert diffuse (no noise).
    lit.spread = [max(abs(px[i * ch + c] - mean[c]) for i in range(n)) / max(mean[c], 1e-30) for c in range(3)]
    bpy.data.images.remove(img)
    return [math.pi * x / math.cos(t) for x in mean]


v = bpy.app.version
with tempfile.TemporaryDirectory() as tmp:
    if what == "furnace":
        k = {0.0: [], 1.0: []}
        for r in k:
            for i in range(0, len(ALBEDO), 3):
                c = ALBEDO[i:i + 3]
                got = furnace(c, r, tmp)
                k[r] += [g / a for g, a in zip(got, c)]
        k0 = [round(x, 4) for x in k[0.0]]
        slope = sum(b - a for a, b in zip(k[0.0], k[1.0])) / len(ALBEDO)
        print(f"SKINBAKE_CALIBRATION ({v[0]}, {v[1]}): {{\"measured_with\": \"Blender {bpy.app.version_string}, "
              f"Cycles CPU, 64 px, {samples} spp (scripts/blender-calibrate.py)\", \"albedo\": {ALBEDO}, "
              f"\"k0\": {tuple(k0)}, \"k_per_roughness\": {slope:.4f}}},")
        print("SKINBAKE_CALIBRATION_RAW", {r: [round(x, 4) for x in v] for r, v in k.items()})
    elif what == "pixel":
        pixel = 0.02 / 24                 # lit(): ortho_scale 0.02 over 24 px
        diffuse, walk = [0.0], []
        for i in range(0, len(PIXEL_FRACTIONS), 3):
            fr = PIXEL_FRACTIONS[i:i + 3]
            got = lit((0.3,) * 3, 1.0, 0.0, tmp, [f * pixel for f in fr])
            for f, r, sp in zip(fr, got, lit.spread):
                dif = abs(r - 0.3) < 1e-4 and sp < 1e-4
                (diffuse if dif else walk).append(f)
                print("SKINBAKE_PIXEL_RADIUS", f, f"{r:.5f}", f"spread {sp:.2e}", "diffuse" if dif else "walk")
        print("SKINBAKE_PIXEL", max(diffuse), min(walk) if walk else "none",
              calibration.sss_diffuse_below_pixels())
    elif what == "check":
        c = calibration.view_measurement()
        if c is None:
            raise SystemExit(f"Blender {bpy.app.version_string} has no VIEW_RESPONSE to check")
        err = []
        for cv, sun_deg in ((0.45, 60.0), (1.0, 0.0)):
            bases = (0.02, 0.1, 0.45)
            for b, r in zip(bases, lit(bases, cv, sun_deg, tmp)):
                err.append(r / calibration.view_response(b, cv, c) - 1)
        print("SKINBAKE_VIEW_CHECK", f"{max(abs(e) for e in err):.4f}", " ".join(f"{e:+.4f}" for e in err))
    else:
        base = sorted(VIEW_BASE)
        rows = []
        for cv in VIEW_COS:
            got = {}
            for i in range(0, len(VIEW_BASE), 3):
                c = VIEW_BASE[i:i + 3]
                for b, r in zip(c, lit(c, cv, 0.0, tmp)):
                    got[b] = r / b
            rows.append(tuple(round(got[b], 4) for b in base))
            print("SKINBAKE_VIEW_ROW", cv, rows[-1], flush=True)
        # The light direction does not matter in 4.x/5.x: the same at a sun 60 deg off the normal.
        chk = []
        for cv in (0.3, 1.0):
            c = (0.02, 0.1, 0.45)
            r60 = lit(c, cv, 60.0, tmp)
            r0 = lit(c, cv, 0.0, tmp)
            chk += [round(a / b - 1, 4) for a, b in zip(r60, r0)]
        print(f"SKINBAKE_CALIBRATION_VIEW ({v[0]}, {v[1]}): {{\"measured_with\": \"Blender {bpy.app.version_string}, "
              f"Cycles CPU, 24 px, {samples} spp (scripts/blender-calibrate.py -- view)\", \"base\": {tuple(base)}, "
              f"\"cos_view\": {VIEW_COS}, \"k\": {tuple(rows)}, \"sun60_vs_sun0\": {tuple(chk)}}},")
