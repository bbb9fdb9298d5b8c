#!/bin/sh
# The showcase gallery of docs/showcase.md, regenerated from one run of scripts/demo.sh (issue 24):
#
#   scripts/demo.sh && scripts/gallery-showcase.sh [DEMO_DIR [WORK_DIR]]   (out/demo, out/gallery)
#
# Copies the demo's pictures to docs/img/showcase-*.png (head, complexions, close-up, ear glow,
# the Blender head) and renders the five-minute Blender material (scripts/blender_five_minute.py:
# one Principled BSDF, random-walk subsurface, radius 3.67/1.37/0.68 mm, no maps) in the same view
# and light, 640x480, SAMPLES (default 32) samples; docs/img/showcase-vs-blender.png is the heads
# side by side at 480x360 each: POV-Ray (exact mode), Blender (translucent mode, if the demo ran
# with BLENDER_HEAD=1), the five-minute material; docs/img/showcase-modes.png is exact vs
# translucent vs the five-minute material, front and back-lit, with one bake (below).  Nothing is cropped or retouched; POV-Ray lays the panels side by side.
# Environment: POVRAY (default povray), BLENDER (default blender); PARTIAL=1: a picture the demo
# did not (yet) make leaves the old copy in docs/img, with a message naming it.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
demo=$(cd "${1:-$top/out/demo}" && pwd)
work=${2:-$top/out/gallery}
img=$top/docs/img
mkdir -p "$work" "$img"
work=$(cd "$work" && pwd)
# copy DEMO_NAME GALLERY_NAME: one picture; with PARTIAL=1 a missing one leaves the old copy.
copy() {
	if [ -f "$demo/$1.png" ]; then
		cp "$demo/$1.png" "$img/showcase-$2.png"
	elif [ "${PARTIAL:-0}" = 1 ]; then
		echo "gallery-showcase.sh: $demo/$1.png is missing: docs/img/showcase-$2.png NOT regenerated" >&2
	else
		echo "gallery-showcase.sh: $demo/$1.png is missing (run scripts/demo.sh; PARTIAL=1 keeps the" \
			"old copy)" >&2
		exit 1
	fi
}
for f in human-head; do
	[ -f "$demo/$f.png" ] || { echo "gallery-showcase.sh: $demo/$f.png is missing (run scripts/demo.sh)" >&2; exit 1; }
done
copy human-head head
copy complexions complexions
copy human-pores closeup
copy human-head-earglow earglow
[ -f "$demo/blender-head.png" ] && cp "$demo/blender-head.png" "$img/showcase-blender-head.png"
t=$(date +%s)
# The demo's eyes for the five-minute head too (scripts/eye_texture.py needs numpy, which
# Blender's Python lacks): the model's texture recoloured here.
py=$top/.venv/bin/python
[ -x "$py" ] || py=python3
mkdir -p "$work/model"
(cd "$work/model" && unzip -o -q /usr/share/assimp/models/Collada/human.zae textures/brown_eye.png) &&
	"$py" "$top/scripts/eye_texture.py" "$work/model/textures/brown_eye.png" "$work/eyes.png" ||
	{ echo "gallery-showcase.sh: could not recolour the model's eye texture" >&2; exit 1; }
# (kept from an earlier run into the same WORK_DIR, unless blender_five_minute.py is newer)
[ "$work/five-minute.png" -nt "$top/scripts/blender_five_minute.py" ] ||
	nice "${BLENDER:-blender}" -b --factory-startup --python "$top/scripts/blender_five_minute.py" -- \
	"$work/five-minute.png" --size 640x480 --samples "${SAMPLES:-32}" --eyes "$work/eyes.png" \
	>"$work/five-minute.log" 2>&1 || { tail -5 "$work/five-minute.log" >&2; exit 1; }
echo "gallery-showcase.sh: five-minute material: $(($(date +%s) - t)) s wall"

# The heads in one row, 480x360 each (sRGB in, sRGB out): POV-Ray, Blender's translucent head
# (when the demo made it: BLENDER_HEAD=1), the five-minute material.
panels="$demo/human-head.png"
[ -f "$demo/blender-head.png" ] && panels="$panels $demo/blender-head.png"
panels="$panels $work/five-minute.png"
set -- $panels
w=$((480 * $#))
n=0
{
	echo "#version 3.7;"
	echo "global_settings { assumed_gamma 1.0 }"
	echo "camera { orthographic location <$#/2,0.5,-1> look_at <$#/2,0.5,0> right x*$# up y }"
	for p in "$@"; do
		echo "box { <0,0,0>, <1,1,0.01> texture { pigment { image_map { png \"$p\" once interpolate 2 } }"
		echo "  finish { emission 1 diffuse 0 ambient 0 } } translate x*$n }"
		n=$((n + 1))
	done
} >"$work/vs.pov"
(cd "$work" && "${POVRAY:-povray}" +Ivs.pov "+O$img/showcase-vs-blender.png" +W$w +H360 -D +A0.1 \
	>vs.log 2>&1) || { tail -5 "$work/vs.log" >&2; exit 1; }
# Exact vs translucent vs the five-minute material, front and back-lit, 320x240 each, one bake
# (`paper`, the one scripts/demo-translucent.sh bakes): front = scenes/showcase-key.scene (the
# showcase's view and key alone), back = scenes/human-head-earglow.scene (the demo's ear glow).
# docs/img/showcase-modes.png: top row front, bottom row back; exact, translucent, five-minute.
# Each step's wall and CPU seconds go to WORK_DIR/modes-times.txt (docs/showcase.md quotes them).
bake=$demo/paper-translucent
[ -f "$bake/manifest.json" ] || { echo "gallery-showcase.sh: $bake is missing (scripts/demo.sh bakes it)" >&2; exit 1; }
times=$work/modes-times.txt
: >"$times"
# timed NAME COMMAND...: run it, append "NAME wall user+system" to modes-times.txt.
timed() {
	tn=$1
	shift
	/usr/bin/time -f "$tn %e %U %S" -a -o "$times" "$@"
}
B=$top/skinbake
for mode in exact translucent; do
	d=$work/front-$mode
	rm -rf "$d"
	timed "front-$mode-export" nice "$B" export pov --scene "$top/scenes/showcase-key.scene" --bake "$bake" \
		--mode $mode --out "$d" >"$d.log" 2>&1 || { cat "$d.log" >&2; exit 1; }
	# the demo's eyes (scripts/demo.sh's render())
	"$py" "$top/scripts/eye_texture.py" "$d/showcase-key_eyes_texture.png" "$work/eyes-$mode.png" &&
		mv "$work/eyes-$mode.png" "$d/showcase-key_eyes_texture.png"
	(cd "$d" && timed "front-$mode-render" nice "${POVRAY:-povray}" showcase-key.ini >"../front-$mode.povray.log" 2>&1) ||
		{ tail -5 "$work/front-$mode.povray.log" >&2; exit 1; }
	cp "$d/showcase-key.png" "$work/front-$mode.png"
done
base=$(sed -n 's/.*SKIN_skin_Lambert = texture { pigment { rgb <\([^>]*\)>.*/\1/p' "$work/front-exact/showcase-key.inc")
for shot in key back; do
	# (kept from an earlier run into WORK_DIR, unless blender_five_minute.py is newer)
	[ "$work/five-$shot.png" -nt "$top/scripts/blender_five_minute.py" ] && continue
	timed "five-minute-$shot" nice "${BLENDER:-blender}" -b --factory-startup --python "$top/scripts/blender_five_minute.py" -- \
		"$work/five-$shot.png" --shot $shot --size 320x240 --samples "${SAMPLES:-32}" --base "$base" \
		--eyes "$work/eyes.png" >"$work/five-$shot.log" 2>&1 || { tail -5 "$work/five-$shot.log" >&2; exit 1; }
done
set -- "$work/front-exact.png" "$work/front-translucent.png" "$work/five-key.png" \
	"$demo/human-head-earglow-exact.png" "$demo/human-head-earglow.png" "$work/five-back.png"
n=0
{
	echo "#version 3.7;"
	echo "global_settings { assumed_gamma 1.0 }"
	echo "camera { orthographic location <1.5,1,-1> look_at <1.5,1,0> right x*3 up y*2 }"
	for p in "$@"; do
		echo "box { <0,0,0>, <1,1,0.01> texture { pigment { image_map { png \"$p\" once interpolate 2 } }"
		echo "  finish { emission 1 diffuse 0 ambient 0 } } translate <$((n % 3)), $((1 - n / 3)), 0> }"
		n=$((n + 1))
	done
} >"$work/modes.pov"
(cd "$work" && "${POVRAY:-povray}" +Imodes.pov "+O$img/showcase-modes.png" +W960 +H480 -D +A0.1 \
	>modes.log 2>&1) || { tail -5 "$work/modes.log" >&2; exit 1; }
echo "gallery-showcase.sh: exact / translucent / five-minute, wall user system seconds:"
cat "$times"

echo "gallery-showcase.sh: wrote $img/showcase-*.png ($(du -ch "$img"/showcase-*.png | tail -1 | cut -f1) in all)"
