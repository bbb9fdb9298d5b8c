# Measure the general mode's calibration constants of this Blender (skinbake_import/calibration.py):
#   blender -b --factory-startup --python-exit-code 1 --python scripts/blender-calibrate.py -- [SAMPLES]
#   (or, for bpy in a venv: PYTHON tests/bpy_blender.py --python scripts/blender-calibrate.py -- [SAMPLES])
# Renders a closed box of Principled BSDF (random-walk subsurface, weight 1, radius 3.6 mm in all
# channels, specular 0) in a white furnace (world 1, no lamp), camera along the normal, for Base
# Colours 0.05 ... 0.95 at roughness 0 and 1, and prints the rendered / requested albedo as a
# Python dict entry to paste into calibration.MEASURED.  About 2 minutes at 256 samples.
import os
import sys
import tempfile

import bpy

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "exporters", "blender"))
from skinbake_import import nodes, scene  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
samples = int(args[0]) if args else 256
ALBEDO = (0.05, 0.15, 0.3, 0.6, 0.8, 0.95)


def furnace(colour, roughness, tmp):
    sc, ob = scene.build_scene({"exact": {"sun_direction": [0, 0, 1]}}, "box", 64, samples, 1.0, 0.0, (90, 0))
    mat = bpy.data.materials.new("furnace")
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
    b.inputs["Subsurface Radius"].default_value = (3.6e-3,) * 3
    nodes.sock(b.inputs, "Specular", "Specular IOR Level").default_value = 0.0
    b.inputs["Roughness"].default_value = roughness
    tr.link(b.outputs["BSDF"], out.inputs["Surface"])
    ob.data.materials.append(mat)
    return scene.render(sc, os.path.join(tmp, "f.exr"))


k = {0.0: [], 1.0: []}
with tempfile.TemporaryDirectory() as tmp:
    for r in k:
        for i in range(0, len(ALBEDO), 3):
            c = ALBEDO[i:i + 3]
            got = furnace(c, r, tmp)
            k[r] += [g / a for g, a in zip(got, c)]
k0 = [round(x, 4) for x in k[0.0]]
slope = sum(b - a for a, b in zip(k[0.0], k[1.0])) / len(ALBEDO)
v = bpy.app.version
print(f"SKINBAKE_CALIBRATION ({v[0]}, {v[1]}): {{\"measured_with\": \"Blender {bpy.app.version_string}, Cycles CPU, "
      f"64 px, {samples} spp (scripts/blender-calibrate.py)\", \"albedo\": {ALBEDO}, \"k0\": {tuple(k0)}, "
      f"\"k_per_roughness\": {slope:.4f}}},")
print("SKINBAKE_CALIBRATION_RAW", {r: [round(x, 4) for x in v] for r, v in k.items()})
