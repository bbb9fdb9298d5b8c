#!/bin/sh
# The POV-Ray gallery of docs/pov.md: the MakeHuman head of
# scenes/human-head.scene in several complexions side by side
# (docs/img/pov-human-complexions.png), and with and without sebum under a
# grazing key light (docs/img/pov-human-sebum.png).  Each preset is baked as
# scripts/demo.sh bakes paper (10 incidence nodes, 5 % RMS error); the panels
# are 320x240 and POV-Ray itself lays them side by side.
#
#   scripts/render-gallery.sh [WORKDIR]      (default ./gallery-work)
#
# With SHOWCASE=1 it makes the showcase gallery of docs/showcase.md instead: scripts/demo.sh's
# pictures (DEMO, default out/demo; run the demo first) copied to docs/img/showcase-*.png, and the
# demo's head side by side with the five-minute Blender material in the same view and light
# (scripts/blender_five_minute.py, 640x480, SAMPLES default 32): docs/img/showcase-vs-blender.png.
#
# Environment: SKINBAKE (default ./skinbake), POVRAY (default povray), BLENDER (default blender).
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
SKINBAKE=${SKINBAKE:-./skinbake}
POVRAY=${POVRAY:-povray}
work=${1:-gallery-work}
mkdir -p "$work" "$top/docs/img"
SKINBAKE=$(cd "$(dirname "$SKINBAKE")" && pwd)/$(basename "$SKINBAKE")
work=$(cd "$work" && pwd)

# montage OUT NAME...: the panels in one row, by POV-Ray (sRGB in, sRGB out); panels PW x PH.
PW=320 PH=240
montage() {
	m_out=$1
	shift
	n=$#
	{
		echo "#version 3.7;"
		echo "global_settings { assumed_gamma 1.0 }"
		echo "camera { orthographic location <$n/2,0.5,-1> look_at <$n/2,0.5,0> right x*$n up y }"
		i=0
		for p in "$@"; do
			echo "box { <0,0,0>, <1,1,0.01> texture { pigment { image_map { png \"$work/$p.png\" once interpolate 2 } }"
			echo "  finish { emission 1 diffuse 0 ambient 0 } } translate x*$i }"
			i=$((i + 1))
		done
	} >"$work/montage.pov"
	(cd "$work" && "$POVRAY" +Imontage.pov "+O$m_out" "+W$((PW * n))" "+H$PH" -D +A0.1 >montage.log 2>&1) ||
		{ tail -5 "$work/montage.log"; exit 1; }
	echo "wrote $m_out"
}

if [ "${SHOWCASE:-0}" = 1 ]; then
	demo=$(cd "${DEMO:-$top/out/demo}" && pwd)
	for f in human-head complexions human-pores human-head-earglow; do
		[ -f "$demo/$f.png" ] || { echo "render-gallery.sh: $demo/$f.png is missing (run scripts/demo.sh)" >&2; exit 1; }
	done
	cp "$demo/human-head.png" "$top/docs/img/showcase-head.png"
	cp "$demo/complexions.png" "$top/docs/img/showcase-complexions.png"
	cp "$demo/human-pores.png" "$top/docs/img/showcase-closeup.png"
	cp "$demo/human-head-earglow.png" "$top/docs/img/showcase-earglow.png"
	cp "$demo/human-head.png" "$work/pov-head.png"
	t=$(date +%s)
	[ -f "$work/five-minute.png" ] ||	# kept from an earlier run of the same WORKDIR
		"${BLENDER:-blender}" -b --factory-startup --python "$top/scripts/blender_five_minute.py" -- \
			"$work/five-minute.png" --size 640x480 --samples "${SAMPLES:-32}" >"$work/five-minute.log" 2>&1 ||
		{ tail -5 "$work/five-minute.log"; exit 1; }
	echo "five-minute Blender material: $(($(date +%s) - t)) s wall"
	PW=640 PH=480
	montage "$top/docs/img/showcase-vs-blender.png" pov-head five-minute
	exit 0
fi

[ -f "$work/face/height.png" ] ||
	"$SKINBAKE" texture --site face --size 512 --tile-mm 10 --out "$work/face" --quiet

# panel NAME PRESET SCENE: render SCENE with a bake of PRESET to $work/NAME.png
panel() {
	[ -f "$work/bake-$2/manifest.json" ] ||
		"$SKINBAKE" bake --preset "$2" --theta-nodes 10 --target-error 0.05 --batch-photons 1000 \
			--out "$work/bake-$2" --quiet
	sed "s/^preset = .*/preset = $2/" "$3" >"$work/$1.scene"
	"$SKINBAKE" export pov --scene "$work/$1.scene" --bake "$work/bake-$2" --textures "$work/face" \
		--size 320x240 --out "$work/$1" >/dev/null 2>"$work/$1.log" || { cat "$work/$1.log"; exit 1; }
	(cd "$work/$1" && "$POVRAY" "$1.ini" >pov.log 2>&1) || { tail -5 "$work/$1/pov.log"; exit 1; }
	cp "$work/$1/$1.png" "$work/$1.png"
	echo "$1: $2"
}


for p in very-fair-dry fair-oily medium-oily olive-oily brown-oily dark-oily; do
	panel "c-$p" "$p" "$top/scenes/human-head.scene"
done
montage "$top/docs/img/pov-human-complexions.png" c-very-fair-dry c-fair-oily c-medium-oily c-olive-oily \
	c-brown-oily c-dark-oily

# Sebum at grazing light: the key light high above the brow, raking the
# forehead and cheekbones (from the side its terminator would run down the
# face's midline, where the coarse mesh's facets make it a hard line).
sed 's/^position = -900 2300 -1400$/position = -700 2600 -300/' "$top/scenes/human-head.scene" >"$work/grazing.scene"
for p in paper paper-dry; do
	panel "s-$p" "$p" "$work/grazing.scene"
done
montage "$top/docs/img/pov-human-sebum.png" s-paper s-paper-dry
