#!/bin/sh
# The POV-Ray exporter with the real POV-Ray: accuracy of the lit tables
# against the C-side evaluation, shadows, bump maps and tiling, every
# shipped scene, and bad input.  Renders are tiny and 16-bit linear
# (+FN16 File_Gamma=1.0); tests/pov_compare does the numbers.
. "$top_srcdir/tests/tap.sh"

CMP="$top_builddir/tests/pov_compare"
SC="$top_srcdir/scenes"
TD="$top_srcdir/tests/data/pov"
DATA="$top_srcdir/exporters/pov"

. "$top_srcdir/tests/lib/pov.sh"
pov_require

# export OUT [options]: skinbake export pov, output in $tmpd/OUT
export_pov() {
	e_out=$1
	shift
	"$SKINBAKE" export pov --out "$tmpd/$e_out" --data-dir "$DATA" "$@" >"$tmpd/$e_out.stdout" 2>"$tmpd/$e_out.stderr"
}

# A small real bake (coarse, few photons: a few seconds) and micro-geometry.
B="$tmpd/bake"
if "$SKINBAKE" bake --preset paper --out "$B" --theta-nodes 4 --resolution 9x9 --estimator bins \
	--max-photons 1e6 --batch-photons 4000 --target-error 0 --quiet >"$tmpd/bake.log" 2>&1; then
	ok "small bake of preset paper"
else
	fail "small bake of preset paper: $(tail -3 "$tmpd/bake.log")"
	tap_done
	exit 1
fi
TX="$tmpd/tex"
if "$SKINBAKE" texture --site face --size 64 --tile-mm 4 --out "$TX" --quiet >"$tmpd/tex.log" 2>&1; then
	ok "micro-geometry maps (skinbake texture)"
else
	fail "skinbake texture: $(tail -2 "$tmpd/tex.log")"
	"$CMP" mkheight --out "$TX" --kind sine
fi

# 1. Accuracy: one parallel light, orthographic camera (2-D table).
if export_pov sphere --scene "$SC/sphere.scene" --bake "$B" && pov_render "$tmpd/sphere" sphere 128 128; then
	r=$("$CMP" expect --scene "$SC/sphere.scene" --bake "$B" --render "$tmpd/sphere/r.png" --tol 0.005)
	check "sphere: parallel light, orthographic: $r (<= 0.5 %)" test $? -eq 0
else
	fail "sphere scene export/render: $(cat "$tmpd/sphere.stderr")"
fi

# 2. Point light and perspective camera (3-D table with the gamma axis).
if export_pov point --scene "$TD/point.scene" --bake "$B" && pov_render "$tmpd/point" point 96 96; then
	grep -q "light-view angles" "$tmpd/point.stderr"
	check "point light + perspective uses the light-view angle axis" test $? -eq 0
	r=$("$CMP" expect --scene "$TD/point.scene" --bake "$B" --render "$tmpd/point/r.png" --tol 0.01)
	check "point light, perspective: $r (<= 1 %)" test $? -eq 0
else
	fail "point scene export/render: $(cat "$tmpd/point.stderr")"
fi

# 3. Two lights against the sum of single-light renders (the scene with
#    one of its lights removed, each with its own table): the one-pass
#    mixture (auto picks it here: parallel lights, orthographic camera) and
#    the passes (one POV-Ray run, one light layer of the skin per light).
#    The background is in the key-only render alone.
sed '/^\[light fill\]/,/^$/d' "$SC/two-lights.scene" >"$tmpd/key-only.scene"
sed '/^\[light key\]/,/^$/d; s/^background.*/background = 0 0 0/' "$SC/two-lights.scene" >"$tmpd/fill-only.scene"
if export_pov two --scene "$SC/two-lights.scene" --bake "$B" && pov_render "$tmpd/two" two-lights 128 128 &&
	export_pov k1 --scene "$tmpd/key-only.scene" --bake "$B" && pov_render "$tmpd/k1" key-only 128 128 &&
	export_pov k2 --scene "$tmpd/fill-only.scene" --bake "$B" && pov_render "$tmpd/k2" fill-only 128 128 &&
	export_pov twop --scene "$SC/two-lights.scene" --bake "$B" --lights passes && pov_render "$tmpd/twop" two-lights 128 128; then
	grep -q "mixture table would be 0.00 % off.*so mixture" "$tmpd/two.stderr"
	check "two parallel lights, orthographic camera: auto estimates the mixture exact and picks it" test $? -eq 0
	r=$("$CMP" sum --render "$tmpd/two/r.png" --parts "$tmpd/k1/r.png" "$tmpd/k2/r.png" --tol 0.01)
	check "two lights, mixture table vs sum of single-light renders: $r (<= 1 %)" test $? -eq 0
	r=$("$CMP" expect --scene "$tmpd/key-only.scene" --bake "$B" --render "$tmpd/k1/r.png" --tol 0.005)
	check "two lights, key light alone: $r" test $? -eq 0
	r=$("$CMP" sum --render "$tmpd/twop/r.png" --parts "$tmpd/k1/r.png" "$tmpd/k2/r.png" --tol 0.005)
	check "two lights, passes as light layers in one run vs sum of single-light renders: $r (<= 0.5 %)" test $? -eq 0
	check "passes in one run: no combining files" test ! -e "$tmpd/twop/two-lights_combine.pov"
else
	fail "two-light export/render: $(cat "$tmpd/two.stderr" "$tmpd/twop.stderr" "$tmpd/k1.stderr")"
fi

# 3b. Passes where the skin cannot be layered (the hand): animation frames
#     to .hdr summed by POV-Ray; BASE.sh does both steps.
if export_pov frames --scene "$TD/frames.scene" --bake "$B" --lights passes &&
	pov_render "$tmpd/frames" frames 64 64 +KFI1 +KFF2 &&
	(cd "$tmpd/frames" && sh frames.sh +W64 +H64 -A >sh.log 2>&1 &&
		"$POVRAY" frames_combine.ini +W64 +H64 +FN16 File_Gamma=1.0 +Oc.png >c.log 2>&1); then
	check "frames: frames.sh writes frames.png" test -s "$tmpd/frames/frames.png"
	r=$("$CMP" sum --render "$tmpd/frames/c.png" --parts "$tmpd/frames/r1.png" "$tmpd/frames/r2.png" --tol 0.01)
	check "frames summed by POV-Ray from .hdr: $r (<= 1 %)" test $? -eq 0
else
	fail "frames: $(cat "$tmpd/frames.stderr" "$tmpd/frames/sh.log" 2>/dev/null | tail -5)"
fi

# 4. Shadows: an occluder darkens exactly the pixels the C-side shadow rays
#    say (pov_compare fails on a lit pixel that should be dark and counts them).
if export_pov shadow --scene "$TD/shadow.scene" --bake "$B" && pov_render "$tmpd/shadow" shadow 96 96; then
	r=$("$CMP" expect --scene "$TD/shadow.scene" --bake "$B" --render "$tmpd/shadow/r.png" --tol 0.005)
	rc=$?
	n=$(echo "$r" | sed -n 's/.*shadowed \([0-9]*\).*/\1/p')
	check "shadow: $r" test $rc -eq 0 -a "${n:-0}" -gt 50
else
	fail "shadow scene export/render: $(cat "$tmpd/shadow.stderr")"
fi

# 5. Bump maps change the shading; the tiled patch shows no seam at the
#    tile boundary (x = 0: column 48 of 96); a non-tileable map does.
if export_pov bump --scene "$TD/bump.scene" --bake "$B" --textures "$TX" && pov_render "$tmpd/bump" bump 96 96 &&
	export_pov flat --scene "$TD/bump.scene" --bake "$B" && pov_render "$tmpd/flat" bump 96 96; then
	grep -q "bump_map { png" "$tmpd/bump/bump.inc"
	check "bump map declared as 16-bit png bump_map" test $? -eq 0
	r=$("$CMP" differ --render "$tmpd/bump/r.png" --other "$tmpd/flat/r.png" --min 0.02)
	check "bump map changes the shading: $r" test $? -eq 0
	r=$("$CMP" seam --render "$tmpd/bump/r.png" --column 48 --max 2)
	check "tiled patch, no seam at the tile boundary: $r" test $? -eq 0
	"$CMP" mkheight --out "$tmpd/ramp" --kind ramp
	if export_pov rampo --scene "$TD/bump.scene" --bake "$B" --textures "$tmpd/ramp" && pov_render "$tmpd/rampo" bump 96 96; then
		r=$("$CMP" seam --render "$tmpd/rampo/r.png" --column 48 --max 2)
		check "negative control: a non-tileable map shows a seam: $r" test $? -ne 0
	else
		fail "ramp height map export/render"
	fi
else
	fail "bump scene export/render: $(cat "$tmpd/bump.stderr" "$tmpd/flat.stderr")"
fi

# 6. Every shipped scene renders without a POV-Ray error or warning (tiny,
#    no antialiasing); passes also through their .ini files.
for f in "$SC"/*.scene; do
	n=$(basename "$f" .scene)
	if export_pov "s-$n" --scene "$f" --bake "$B" --textures "$TX" && pov_render "$tmpd/s-$n" "$n" 64 48; then
		ok "scene $n renders without error or warning"
	else
		fail "scene $n: $(cat "$tmpd/s-$n.stderr")"
	fi
done
if export_pov s-sep --scene "$SC/two-lights.scene" --bake "$B" --lights separable &&
	pov_render "$tmpd/s-sep" two-lights 64 48; then
	ok "separable scene renders"
else
	fail "separable scene: $(cat "$tmpd/s-sep.stderr")"
fi
grep -q "separable fit.*rms error" "$tmpd/s-sep.stderr"
check "separable export prints the fit error" test $? -eq 0

grep -q "height map box-filtered 64 -> [1-3][0-9] px" "$tmpd/s-hand.stderr"
check "bump map box-filtered to the pixel footprint (hand scene)" test $? -eq 0
if export_pov s-nofilt --scene "$SC/hand.scene" --bake "$B" --textures "$TX" --bump-filter off &&
	! grep -q "box-filtered" "$tmpd/s-nofilt.stderr" && cmp -s "$TX/height.png" "$tmpd/s-nofilt/hand_skin_height.png"; then
	ok "--bump-filter off copies the height map unchanged"
else
	fail "--bump-filter off"
fi

# --plan: the angles a flat patch needs, and nothing written.
r=$("$SKINBAKE" export pov --scene "$TD/bump.scene" --plan --out "$tmpd/plan")
echo "$r" | grep -q "theta-in 69.04 " && test ! -e "$tmpd/plan"
check "--plan names the incidence angle of the patch and writes nothing" test $? -eq 0

# 7. The include file alone (lights and camera on the command line),
#    included twice (guarded), with the caller's #version kept.
if export_pov inc --bake "$B" --light type=point,position=2:1.5:-2.5,name=key \
	--camera type=perspective,location=0:0:-3,angle=40; then
	cat >"$tmpd/inc/use.pov" <<'POV'
#version 3.7;
global_settings { assumed_gamma 1.0 }
#include "skin.inc"
#include "skin.inc"
#if (version != 3.7) #error "version not restored" #end
camera { perspective location <0,0,-3> look_at 0 angle 40 right x up y }
light_source { SKIN_Light_key }
sphere { 0, 1 texture { pigment { SKIN_skin_Pigment } finish { SKIN_skin_Finish } } }
POV
	check "include-only export, included twice" pov_render "$tmpd/inc" use 32 32
else
	fail "include-only export: $(cat "$tmpd/inc.stderr")"
fi

# 8. Bad input: clear errors, exit status 2, no output files.
export_pov bad1 --scene "$SC/sphere.scene" --bake "$tmpd/no-such-bake"
rc=$?
check "missing bake: exit 2" test $rc -eq 2
grep -q "no-such-bake" "$tmpd/bad1.stderr"
check "missing bake: message names the directory ($(head -1 "$tmpd/bad1.stderr"))" test $? -eq 0
check "missing bake: no output" test ! -e "$tmpd/bad1"
sed 's/^radius = 1$/radius = 1\nradiuss = 2/' "$SC/sphere.scene" >"$tmpd/typo.scene"
export_pov bad2 --scene "$tmpd/typo.scene" --bake "$B"
rc=$?
check "unknown scene key: exit 2" test $rc -eq 2
grep -q "typo.scene:[0-9]*: \[object ball\]: unknown key 'radiuss'" "$tmpd/bad2.stderr"
check "unknown scene key: file:line and key ($(head -1 "$tmpd/bad2.stderr"))" test $? -eq 0
check "unknown scene key: no output" test ! -e "$tmpd/bad2"
printf '[scene]\ntitle = %s\n' "$(printf '%0250d' 0)" > "$tmpd/long.scene"
"$SKINBAKE" export pov --scene "$tmpd/long.scene" --bake "$B" --out "$tmpd/long" 2>"$tmpd/long.stderr"
rc=$?
check "scene with an over-long line: exit 2, line named, no output" \
	sh -c "[ $rc -eq 2 ] && grep -q 'long.scene:2: line 2 is longer than 199' '$tmpd/long.stderr' && [ ! -e '$tmpd/long' ]"
export_pov bad3 --scene "$SC/sphere.scene" --bake "$B" --textures "$tmpd/no-such-tex"
check "missing textures: exit 2" test $? -eq 2
export_pov bad4 --scene "$SC/sphere.scene" --bake "$B" --nodes 300
check "--nodes 300: exit 2" test $? -eq 2
grep -q "out of range" "$tmpd/bad4.stderr"
check "--nodes 300: range in the message" test $? -eq 0

# 9. --help lists every option.
h=$("$SKINBAKE" export pov --help)
missing=""
for o in scene light camera bake textures out name lights nodes gamma-nodes mix-nodes data-dir analytic plan help; do
	echo "$h" | grep -q -- "--$o" || missing="$missing --$o"
done
check "export pov --help lists every option${missing:+ (missing:$missing)}" test -z "$missing"

tap_done
