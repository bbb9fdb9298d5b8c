#!/bin/sh
# The Blender half of the translucent gallery (docs/translucency.md): the MakeHuman head in
# Cycles (Debian's Blender 3.4), exact mode, translucent mode (Cycles' Subsurface Scattering node
# fitted to the bake's Rd(r) beside the rest of the table) and the five-minute baseline (a
# Principled BSDF, random walk, radius 3.67/1.37/0.68 mm after Jensen et al. 2001, colour = the
# baked albedo), under human_scene.py's key sun and fill (front) and with the sun moved behind the
# head (back).  scripts/render-translucent-blender.sh [OUT_DIR] (default out/translucent);
# SIZE (320x240), SAMPLES (32).  Writes OUT_DIR/blender-{front,back}-{exact,translucent,baseline}.png
# and appends "label wall_s cpu_s" lines to OUT_DIR/times.txt.  Run after scripts/setup.sh.
# BLENDER=tests/bpy-blender BPY_PYTHON=.venv/bin/python renders in a bpy venv instead (the
# translucent set holds a fit per calibrated Blender; the importer takes its own).
set -eu
cd "$(dirname "$0")/.."
B=${SKINBAKE:-./skinbake}
out=${1:-out/translucent}
size=${SIZE:-320x240}
samples=${SAMPLES:-32}
imp=exporters/blender/import_skin.py
bl=${BLENDER:-blender}
BL() { "$bl" -b -noaudio --python-exit-code 1 "$@"; }
mkdir -p "$out"
[ -f "$out/bake/manifest.json" ] || $B bake --preset paper --theta-nodes 10 --out "$out/bake" --quiet
$B export blender --bake "$out/bake" --out "$out/bl-exact" --mode exact >/dev/null
$B export blender --bake "$out/bake" --out "$out/bl-translucent" --mode translucent >/dev/null
BL --factory-startup --python exporters/blender/human_scene.py -- "$out/bl-scene.blend" --size "$size" \
	--samples "$samples" >"$out/bl-scene.log" 2>&1
# The baseline: what a user sets up in five minutes.
cat >"$out/baseline.py" <<'PY'
import json, sys
import bpy
m = json.load(open(sys.argv[sys.argv.index("--") + 1]))
mat = bpy.data.materials.new("five-minute skin")
mat.use_nodes = True
p = mat.node_tree.nodes["Principled BSDF"]
p.subsurface_method = "RANDOM_WALK"
alb = (*m["albedo_rgb"], 1.0)
p.inputs["Base Color"].default_value = alb
if "Subsurface Color" in p.inputs:
    p.inputs["Subsurface Color"].default_value = alb
p.inputs["Subsurface"].default_value = 1.0
p.inputs["Subsurface Radius"].default_value = (0.00367, 0.00137, 0.00068)
p.inputs["Roughness"].default_value = 0.45
body = bpy.data.objects["human-base"]
body.data.materials.clear()
body.data.materials.append(mat)
bpy.ops.wm.save_as_mainfile(filepath=sys.argv[sys.argv.index("--") + 2])
PY
# back: the key sun from behind the head, right and a little above; the fill dimmed.
back='import bpy; from mathutils import Vector; k = bpy.data.objects["Key"]; k.rotation_euler = Vector((0.45, 0.85, 0.35)).normalized().to_track_quat("Z", "Y").to_euler(); bpy.data.lights["Fill"].energy = 2.0; bpy.ops.wm.save_mainfile()'
for shot in front back; do
	for mode in exact translucent baseline; do
		f="$out/blender-$shot-$mode"
		if [ $mode = baseline ]; then
			BL "$out/bl-scene.blend" --python "$out/baseline.py" -- "$out/bl-exact/manifest.json" "$f.blend" \
				>"$f.log" 2>&1
		else
			BL "$out/bl-scene.blend" --python "$imp" -- "$out/bl-$mode" --objects human-base --mode exact \
				--uv-size 0.964 --save "$f.blend" >"$f.log" 2>&1
		fi
		[ $shot = back ] && BL "$f.blend" --python-expr "$back" >>"$f.log" 2>&1
		/usr/bin/time -f "blender-$shot-$mode %e %U" -a -o "$out/times.txt" \
			"$bl" -b -noaudio "$f.blend" -o "//blender-$shot-$mode-render_" -f 1 >>"$f.log" 2>&1
		mv "$out/blender-$shot-$mode-render_0001.png" "$f.png"
		echo "wrote $f.png"
	done
done
