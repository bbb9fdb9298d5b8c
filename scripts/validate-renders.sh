#!/bin/sh
# Section 5 of the validation report (docs/validation.md): Li & Ng's figures 6
# to 10 rendered by POV-Ray with the `paper` and `paper-dry` bakes: sebum on
# and off (6), Phong / Lambert / subsurface (7), a head with pores and a
# close-up of its cheek (8), the furrow net and its render (9), a hand (10).
# Every picture is at least 480 px on its short side.
#
# Run by scripts/validate.sh after scripts/validate-brdf.sh (whose bakes it
# uses), or alone while developing (it then bakes paper and paper-dry):
#
#   SKINBAKE=./skinbake sh $top_srcdir/scripts/validate-renders.sh
#
# Environment: SKINBAKE, POVRAY, GNUPLOT, THREADS, VALIDATE_WORK,
# VALIDATE_QUICK as in validate.sh (quarter size, no extra antialiasing);
# RENDER_SCALE (1; 0.5 halves every image, for trying the script).  Writes $VALIDATE_WORK/render/section.md,
# $VALIDATE_WORK/render/times.tsv and the images into $VALIDATE_WORK/png.
#
# The human model: the head (figure 8) and the hand (figure 10) are the
# MakeHuman figure of Debian's assimp-testmodels (../shared/notes/human-model.md)
# through the exporter's meshes: scenes/human-head.scene, scenes/human-pores.scene
# and a hand scene generated here.  The model file must be installed
# (scripts/setup.sh); without it the analytic head and hand are rendered and
# the report says so.
set -eu

top_srcdir=${top_srcdir:-$(cd "$(dirname "$0")/.." && pwd)}
SKINBAKE=${SKINBAKE:-./skinbake}
POVRAY=${POVRAY:-povray}
GNUPLOT=${GNUPLOT:-gnuplot}
[ -n "$POVRAY" ] || POVRAY=povray
[ -n "$GNUPLOT" ] || GNUPLOT=gnuplot
THREADS=${THREADS:-0}
SCALE=${RENDER_SCALE:-1}
AA="+A0.05 +AM2 +R3"
if [ "${VALIDATE_QUICK:-0}" = 1 ]; then SCALE=${RENDER_SCALE:-0.25} AA=""; fi
work=${VALIDATE_WORK:-validate-work}
say() { echo "validate:   $*"; }
mkdir -p "$work/png" "$work/render"
work=$(cd "$work" && pwd)
png=$work/png
rn=$work/render
br=$work/brdf
px() { awk -v a="$1" -v s="$SCALE" 'BEGIN { printf "%d", a * s + 0.5 }'; }

# Bakes: those of validate-brdf.sh, or our own.
for p in paper paper-dry; do
	if [ ! -f "$br/bake-$p/manifest.json" ]; then
		say "bake $p (no bake from validate-brdf.sh)"
		mkdir -p "$br"
		"$SKINBAKE" bake --preset "$p" --theta-nodes 8 --out "$br/bake-$p" --batch-photons 2000 \
			--target-error "$([ "${VALIDATE_QUICK:-0}" = 1 ] && echo 0.2 || echo 0.02)" --threads "$THREADS" --quiet
	fi
done
# Micro-geometry maps for every site the scenes use.
# The face map as scripts/demo.sh grows it for the MakeHuman head (10 mm tile).
for s in cheek face hand; do
	tile=""
	[ "$s" = face ] && tile="--tile-mm 10"
	# shellcheck disable=SC2086
	"$SKINBAKE" texture --site "$s" --size 1024 $tile --out "$rn/tex-$s" --quiet
done
model=/usr/share/assimp/models/Collada/human.zae
human=0
[ -f "$model" ] && human=1

# The renders are kept as POV-Ray writes them (8-bit RGB PNG, 100-600 KB):
# re-encoding them with a 256-colour palette (gnuplot's gd terminal, the only
# re-encoder among the dependencies) posterized the head's highlight into a
# grey cross with orange fringes that is not in the render.
# render NAME SCENEFILE WIDTH HEIGHT [POV-Ray options]: export + POV-Ray at
# WIDTH x HEIGHT; on failure the reason goes into the report.
render_failures=""
: >"$rn/times.tsv"
render() {
	n=$1 f=$2 wd=$(px "$3") ht=$(px "$4")
	shift 4
	site=$(sed -n 's/^site *= *//p' "$f" | head -1)
	dry=""
	grep -q '^\[skin dry\]' "$f" && dry="--bake dry=$br/bake-paper-dry"
	# The scene's own size, so that the exporter's bump filter sees the
	# pixel footprint of the image actually rendered.
	awk -v w="$wd" -v h="$ht" '/^\[/ { sec = $0 }
		sec == "[scene]" && /^width *=/ { print "width = " w; nw++; next }
		sec == "[scene]" && /^height *=/ { print "height = " h; next }
		{ print } END { exit nw != 1 }' "$f" >"$rn/$n.scene" || die_scene "$f"
	t0=$(date +%s)
	# shellcheck disable=SC2086
	if ! "$SKINBAKE" export pov --scene "$rn/$n.scene" --bake "$br/bake-paper" $dry --textures "$rn/tex-$site" \
		--data-dir "$top_srcdir/exporters/pov" --out "$rn/$n" >"$rn/$n.log" 2>&1; then
		render_failures="$render_failures
- \`$n\` (\`$(basename "$f")\`): \`skinbake export pov\` failed: $(tail -3 "$rn/$n.log" | tr '\n' ' ' | sed 's/`//g')"
		say "$n: export FAILED"
		return 0
	fi
	wt=""
	[ "$THREADS" -gt 0 ] && wt=+WT$THREADS
	# shellcheck disable=SC2086
	if ! (cd "$rn/$n" && "$POVRAY" "$n.ini" $wt "$@" >pov.log 2>&1) || [ ! -f "$rn/$n/$n.png" ]; then
		render_failures="$render_failures
- \`$n\` (\`$(basename "$f")\`): POV-Ray failed: $(tail -3 "$rn/$n/pov.log" | tr '\n' ' ' | sed 's/`//g')"
		say "$n: POV-Ray FAILED"
		return 0
	fi
	cp "$rn/$n/$n.png" "$png/render-$n.png"
	echo "$n	$(($(date +%s) - t0))	$wd x $ht	$(wc -c <"$png/render-$n.png")" >>"$rn/times.tsv"
	say "$n: $wd x $ht, $(($(date +%s) - t0)) s, $(wc -c <"$png/render-$n.png") bytes"
}
die_scene() { echo "validate-renders: $1 has no width = line in [scene]" >&2; exit 1; }

# Figure 6: sebum on (left) and off (right).  Figure 7: Phong, Lambert, the
# baked BRDF.  Figure 10: the hand.  From the shipped scenes, larger.
render sebum "$top_srcdir/scenes/sebum.scene" 960 480
render shading-models "$top_srcdir/scenes/shading-models.scene" 1350 480
# Bump-mapped skin gets finer antialiasing than the scenes' threshold 0.3,
# which leaves single-sample grain on the pores and a moire of vertical
# stripes near the head's right silhouette (where the bump map is projected
# along the view) at 640 px; +A0.05 +AM2 +R3 removes both (seen side by side)
# and costs about 3 times the render time.
if [ "$human" = 1 ]; then
	# Figure 10: the MakeHuman figure's hand (model x 0.45-0.53 m, y 0.89-1.05 m,
	# z 0.14-0.34 m: it hangs beside the thigh), seen from outside and a little
	# in front, with the hand site's furrow net following the model's UVs.
	cat >"$rn/human-hand-src.scene" <<'EOF'
; Generated by scripts/validate-renders.sh: the hand of the MakeHuman model
; (Debian's assimp-testmodels), seen from outside, with the hand site's
; furrows as a bump map that follows the model's UVs (paper figure 10).
[scene]
title = MakeHuman hand with the baked skin and furrows (paper figure 10)
width = 640
height = 640
unit_mm = 1
background = 0.03 0.03 0.035
antialias = 0.3

[camera]
type = perspective
location = 950 1150 -520
look_at = 497 940 -262
angle = 30

[light key]
type = point
position = 1200 2200 -1500
color = 1 1 1

[light fill]
type = point
position = 1500 600 200
color = 0.3 0.3 0.33

[skin skin]
preset = paper
site = hand

[object body]
shape = mesh
file = /usr/share/assimp/models/Collada/human.zae
mesh = human-baseMesh
scale = 1000
subdivide = 1
EOF
	# shellcheck disable=SC2086
	render hand "$rn/human-hand-src.scene" 640 640 $AA
	# Figure 8: the MakeHuman head under a key and a fill light, and its cheek
	# at 0.04 mm per pixel (the scenes of scripts/demo.sh), where single pores
	# cover several pixels.
	# shellcheck disable=SC2086
	render head "$top_srcdir/scenes/human-head.scene" 640 480 $AA
	# shellcheck disable=SC2086
	render head-closeup "$top_srcdir/scenes/human-pores.scene" 640 480 $AA
else
	# shellcheck disable=SC2086
	render hand "$top_srcdir/scenes/hand.scene" 640 640 $AA
	# shellcheck disable=SC2086
	render head "$top_srcdir/scenes/head.scene" 640 640 $AA
	sed -e 's/^title = .*/title = Cheek close-up with pores (paper figure 8, validation scene)/' \
		-e 's/^location = .*/location = 0.15 -0.05 -2.1/' -e 's/^look_at = .*/look_at = 0.52 -0.2 -0.35/' \
		-e 's/^angle = .*/angle = 16/' -e 's/^position = .*/position = 3 1.5 -1.2/' \
		"$top_srcdir/scenes/head.scene" >"$rn/head-closeup-src.scene"
	# shellcheck disable=SC2086
	render head-closeup "$rn/head-closeup-src.scene" 640 480 $AA
fi
# Figure 9: the furrow net (height map of `skinbake texture --site hand`,
# dark = deep) and the net as a bump map on a flat patch at grazing light.
fn=$(px 512)
printf 'set terminal png size %s,%s\nset output "%s"\nset margins 0,0,0,0\nunset border\nunset tics\nunset key\nunset colorbox\nset palette gray maxcolors 64\nset size ratio -1\nset xrange [-0.5:1023.5]\nset yrange [-0.5:1023.5]\nplot "%s" binary filetype=png using 1 with image\n' \
	"$fn" "$fn" "$png/furrow-net.png" "$rn/tex-hand/furrows_height.png" | "$GNUPLOT"
cat >"$rn/furrow-patch-src.scene" <<'EOF'
; Generated by scripts/validate-renders.sh: the hand furrow net as a bump map
; on a flat patch of skin (1 unit = 1 cm), lit at grazing incidence.
[scene]
title = Furrow net on a flat patch of skin (paper figure 9)
width = 512
height = 512
unit_mm = 10
background = 0 0 0

[camera]
type = orthographic
location = 0 0 -10
look_at = 0 0 0
width = 1.0

[light key]
type = parallel
position = -1000 400 -350
color = 1 1 1

[skin skin]
preset = paper
site = hand

[object patch]
shape = patch
center = 0 0 0
size = 1.2 1.2 0.1
EOF
# shellcheck disable=SC2086
render furrow-patch "$rn/furrow-patch-src.scene" 512 512 $AA

# The section's markdown.
headfig=$(sed -n '1s/.*\(figures* [0-9-]*\).*/\1/p' "$top_srcdir/scenes/head.scene")
handfig=$(sed -n '1s/.*\(figures* [0-9-]*\).*/\1/p' "$top_srcdir/scenes/hand.scene")
fig_note=""
[ "$headfig" = "figure 8" ] && [ "$handfig" = "figure 10" ] ||
	fig_note=" The scene files number them differently: \`head.scene\` says \"${headfig:-no figure}\", \`hand.scene\` \"${handfig:-no figure}\"."
if [ "$human" = 1 ]; then
	human_note="**The head and the hand are the human model**: the MakeHuman figure of Debian's
assimp-testmodels (\`$model\`, one level of subdivision) through the exporter's meshes, its
maps following the model's UVs."
else
	human_note="**The human model is missing** (\`$model\`; scripts/setup.sh installs
assimp-testmodels): the head and the hand are the exporter's analytic shapes (an isosurface head
without ears or hair, a blob-and-sweep hand), so figures 8 and 10 show the skin, not a person."
fi
row() { # name figure text
	f=render-$1.png
	[ "$1" = furrow-net ] && f=furrow-net.png
	if [ -f "$png/$f" ]; then
		sz=$(awk -F'\t' -v n="$1" '$1 == n { print $3 }' "$rn/times.tsv")
		[ "$1" = furrow-net ] && sz="$fn x $fn"
		echo "| $2 | $3 | $sz | ![$1](validation/$f) |"
	else
		echo "| $2 | $3 | - | **failed** (see below) |"
	fi
}
{
	cat <<EOF
Made by POV-Ray from the shipped scenes (\`scenes/*.scene\`, rendered larger than their own
size) and from scenes this script generates (the hand, the furrow patch), with
\`skinbake export pov\`, the \`paper\` and \`paper-dry\` bakes of section 3 (Li & Ng's Tables 1-2,
8 incidence nodes, 470/550/656 nm as B/G/R) and \`skinbake texture\` maps at 1024 px. Figure
numbers follow the paper (head 8, furrow net 9, hand 10).$fig_note

$human_note

| figure | what | size [px] | image |
|---|---|---|---|
EOF
	row sebum 6 "with (left) and without (right) sebum: \`scenes/sebum.scene\`, \`paper\` and \`paper-dry\`"
	row shading-models 7 "Phong, Lambert and the baked BRDF with the same albedo: \`scenes/shading-models.scene\`"
	if [ "$human" = 1 ]; then
		row head 8 "the MakeHuman head with the face's pores and furrows (\`skinbake texture --site face --tile-mm 10\`) as a bump map following the model's UVs, key and fill light: \`scenes/human-head.scene\`"
		row head-closeup 8 "the same head's cheek at 0.04 mm per pixel, so single pores show: \`scenes/human-pores.scene\`"
	else
		row head 8 "a head with pores (\`skinbake texture --site cheek\` as bump map): \`scenes/head.scene\`"
		row head-closeup 8 "close-up of the same head's cheek (about 55 mm across), so single pores show"
	fi
	row furrow-net 9 "the furrow net: furrow height map of \`skinbake texture --site hand\` (one 12 mm tile at 1024 px; dark = deep)"
	row furrow-patch 9 "the furrow net as a bump map on a flat 12 mm patch at grazing light"
	if [ "$human" = 1 ]; then
		row hand 10 "the MakeHuman figure's hand beside its thigh, the hand site's furrows following the model's UVs (scene generated here)"
	else
		row hand 10 "a hand with furrows: \`scenes/hand.scene\`"
	fi
	echo
	if [ -n "$render_failures" ]; then
		echo "**Failed renders** (reported, not fixed here):"
		echo "$render_failures"
	else
		echo "All renders succeeded. Time per figure (export + POV-Ray, s): $(awk -F'\t' '{ printf "%s%s %s", (NR > 1 ? ", " : ""), $1, $2 }' "$rn/times.tsv")."
	fi
	# The paper preset's colour from section 4 when it ran (validate.sh), else unknown.
	lab=$(awk '$1 == "paper" { printf "L* %.0f, a* %.0f, b* %.0f", $2, $3, $4 }' "$work/colour/presets.dat" 2>/dev/null || true)
	cat <<EOF

**What looks wrong** (from looking at these pictures; the text is kept with the script, so check
it when the scenes or the presets change):

- *Colour.* Every figure is a dark, red-brown skin: that is the paper's Tables 1-2 (${lab:-see section 4}
  in section 4), darker and redder than the measured skin colours of section 4 at the same
  lightness; nothing in these figures varies in colour (no freckles, no redness, lips and
  cheeks the same as the forehead).
- *Figure 6.* With sebum the highlight is brighter and tighter; without it, broader and dimmer,
  as the paper says. The sebum sphere's shadow side is a dim blue-grey while the dry sphere
  ends in a hard black terminator: the oily skin has \`reflection = on\` and mirrors the
  background there, which a real film would do too, but only toward grazing views.
- *Figure 7.* Phong gives the sharp white "plastic" highlight, Lambert the flat chalky look, the
  baked BRDF a broad soft sheen, as the paper describes. A BRDF cannot carry light past the
  terminator, so "subsurface" shading shows no translucency at the shadow edge.
EOF
	if [ "$human" = 1 ]; then
		cat <<'EOF'
- *Figure 8, head.* The MakeHuman head reads as a person: nose, lips, eyes and an ear. It is
  bald (the model has no hair), the lips are the colour of the rest of the skin, the irises are
  red-brown without a catch-light, and the forehead's broad sheen looks waxy. Pores and
  furrows are not visible at this size (about 0.45 mm per pixel at the face).
- *Figure 8, cheek at 0.04 mm per pixel.* The furrow net dominates: a dense crackle of fine
  triangles over the whole frame, with the pores as scattered small dark dots. Real cheek skin
  shows its pores first and its furrows faintly; this reads as crackled leather. The frame is
  flat (26 mm of cheek), so the model's curvature shows only as a light gradient.
- *Figure 9.* The net of triangles reads well, the primary furrows darker than the secondary
  ones; on the patch at grazing light the net shows, but it looks like crackle glaze on dark
  leather rather than the diamond pattern of the back of a hand.
- *Figure 10, hand.* The MakeHuman hand beside the thigh reads as a hand (fingers, knuckles,
  nails in the geometry), but the nails have the skin's colour and sheen, the dark gaps
  between the fingers have no translucency, and the furrows show only as a faint grain at
  this size (about 0.47 mm per pixel).
EOF
	else
		cat <<'EOF'
- *Figure 8.* The head is the exporter's analytic isosurface: no eyes, mouth or hair, it reads as
  a mannequin; its far side falls into full black. Pores are hardly visible at 640 px for the
  whole head, hence the close-up, where they read as perforated leather more than as a cheek.
- *Figure 9.* The net of triangles reads well; on the patch it looks like crackle glaze.
- *Figure 10.* The hand is a blob with sphere sweeps: the thumb is a separate sausage, there are
  no nails or knuckles; the furrows show only as a fine grain at this size.
EOF
	fi
} >"$rn/section.md"
