#!/bin/sh
# The demo's cheek close-up in POV-Ray and Blender side by side (issue 24, docs/relief.md section 7):
# skinbake's skin in POV-Ray (scripts/demo.sh's OUT/human-pores.png, rendered again if missing), the
# same maps, relief and view in Blender through import_skin.py (general mode: subsurface under the
# normal map blurred by the mean exit radius, specular under the sharp one), and a Blender user's
# five minutes (scripts/blender_five_minute.py --closeup: one Principled BSDF, no relief).
#   scripts/closeup-compare.sh [OUT]        (default out/demo; run scripts/demo.sh first)
# Writes OUT/closeup-blender.png, OUT/closeup-five-minute.png and OUT/closeup-compare.png (the three,
# left to right).  SIZE (default 480x360) and SAMPLES (default 32) change the Blender renders.
set -eu
cd "$(dirname "$0")/.."
B=${SKINBAKE:-./skinbake}
out=${1:-out/demo}
size=${SIZE:-480x360}
samples=${SAMPLES:-32}
model=/usr/share/assimp/models/Collada/human.zae
BL() { nice blender -b -noaudio --python-exit-code 1 "$@"; }
for f in "$out/fam/family.json" "$out/maps-fair" "$out/cheek/manifest.json" "$out/human-pores.png"; do
	[ -e "$f" ] || { echo "closeup-compare.sh: $f is missing (run scripts/demo.sh first)" >&2; exit 1; }
done
t0=$(date +%s)
echo "== Blender: a user's five minutes, the close-up's view and light ($size, $samples samples)"
BL --factory-startup --python scripts/blender_five_minute.py -- "$out/closeup-five-minute.png" \
	--model "$model" --size "$size" --samples "$samples" --closeup --save "$out/closeup-scene.blend" \
	>"$out/closeup-five-minute.log" 2>&1 || { tail -5 "$out/closeup-five-minute.log" >&2; exit 1; }
echo "== Blender: skinbake's image set (the demo's fair maps and cheek relief), general mode"
$B export blender --family "$out/fam" --maps "$out/maps-fair" --textures "$out/cheek" \
	--out "$out/closeup-set" >"$out/closeup-set.log" 2>&1 || { cat "$out/closeup-set.log" >&2; exit 1; }
# --uv-size: the face's UV density of the body mesh (scripts/render-blender-head.sh).
BL "$out/closeup-scene.blend" --python exporters/blender/import_skin.py -- "$out/closeup-set" \
	--objects human-base --mode general --uv-size 0.964 --render "$out/closeup-blender.png" \
	>"$out/closeup-blender.log" 2>&1 || { tail -5 "$out/closeup-blender.log" >&2; exit 1; }
grep "^import_skin.py" "$out/closeup-blender.log" || true
w=${size%x*} h=${size#*x}
{
	echo "#version 3.7;"
	echo "global_settings { assumed_gamma 1.0 }"
	echo "camera { orthographic location <1.5,0.5,-1> look_at <1.5,0.5,0> right x*3 up y }"
	i=0
	for f in human-pores.png closeup-blender.png closeup-five-minute.png; do
		echo "box { <0,0,0>, <1,1,0.01> texture { pigment { image_map { png \"$f\" once interpolate 2 } }"
		echo "  finish { emission 1 diffuse 0 ambient 0 } } translate x*$i }"
		i=$((i + 1))
	done
} >"$out/closeup-compare.pov"
(cd "$out" && povray +Icloseup-compare.pov +Ocloseup-compare.png +W$((3 * w)) +H"$h" -D +A0.1 \
	>closeup-compare.log 2>&1) || { echo "closeup-compare.sh: see $out/closeup-compare.log" >&2; exit 1; }
echo "wrote $out/closeup-compare.png (POV-Ray, Blender, Blender five minutes) in $(($(date +%s) - t0)) s"
