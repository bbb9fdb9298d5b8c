# Test helper, run inside Blender on a saved .blend:
#   blender -b FILE.blend --python-exit-code 1 --python blender_measure.py -- OUT.exr [REF.exr] [--small]
# renders the loaded scene to OUT.exr (--small: 32 px, 4 samples), prints "SKINBAKE_CENTER r g b" (mean of the centre
# quarter, read back from the file) and, with REF, "SKINBAKE_MAXDIFF d": the largest per-pixel
# difference from REF relative to REF's mean.
import os
import sys

import bpy

sys.dont_write_bytecode = True     # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "exporters", "blender"))
import import_skin  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
if "--small" in args:
    args.remove("--small")
    sc = bpy.context.scene
    sc.render.resolution_x = sc.render.resolution_y = 32
    sc.render.resolution_percentage = 100
    sc.cycles.samples = 4
out = os.path.abspath(args[0])
mean = import_skin.render(bpy.context.scene, out)
print("SKINBAKE_CENTER " + " ".join(f"{x:.6f}" for x in mean))
if len(args) > 1:
    def pixels(path):
        img = bpy.data.images.load(os.path.abspath(path), check_existing=False)
        img.colorspace_settings.name = "Non-Color"
        px = list(img.pixels)
        bpy.data.images.remove(img)
        return px
    a, b = pixels(out), pixels(args[1])
    if len(a) != len(b):
        raise SystemExit(f"blender_measure: {out} and {args[1]} differ in size")
    ref = sum(b) / len(b)
    print(f"SKINBAKE_MAXDIFF {max(abs(x - y) for x, y in zip(a, b)) / ref:.6g}")
