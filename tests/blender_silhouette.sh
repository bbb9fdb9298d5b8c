#!/bin/sh
# Silhouettes of Blender renders against adding-doubling itself (issue 26 item 4; the POV-Ray
# twin is tests/pov_silhouette.sh): a default adding-doubling bake of `paper` (9 x 9), its image
# set on the importer's sphere (128 x 128, Cycles, orthographic reference view, the manifest's sun,
# denoiser off), and per pixel the expected value from adding-doubling point values of the bake's
# own layer stacks at that pixel's angles (tests/blender_brdf --ad, not eval, which the image set
# follows by construction), on the pixels whose exit angle is 70 deg or more (the grazing ring
# that survives the 3 x 3 object mask: 70 to about 83 deg).
#   - exact mode: mean relative error (largest over RGB per pixel) <= 0.5 %, as POV-Ray's test;
#     measured 0.10 % (against eval 0.02 %).  A bake with --theta-nodes 4 (linear in theta_i
#     between 0, 22.5, 45 and 67.5 deg) must fail the same check (measured 10 %).
#   - general mode (the fitted mixture, 64 samples): over the ring, the render's sum divided by
#     the reference's, per channel, within the fit's own stated error (the manifest's
#     rms_error_uniform_rgb of the fit this Blender renders, about 6-12 %); measured on Blender
#     3.4 0.999 / 1.023 / 1.045.
# About 1 minute.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/blender.sh"
imp="$top_srcdir/exporters/blender/import_skin.py"
scn="$top_srcdir/tests/blender_scene.py"
brdf="$top_builddir/tests/blender_brdf"
blender_require
B() { timeout 600 "$BLENDER" -b -noaudio --python-exit-code 1 "$@"; }
# set_up NAME MODE SAMPLES BAKE-ARGS...: bake, export, import onto the sphere, save NAME-MODE.blend
set_up() {
	s_n=$1 s_mode=$2 s_spp=$3
	shift 3
	[ -d "$tmpd/b_$s_n" ] || "$SKINBAKE" bake --preset paper --out "$tmpd/b_$s_n" \
		--resolution 9x9 --r-bins 20 --radial-photons 4000 --quiet "$@" >"$tmpd/$s_n.log"
	[ -d "$tmpd/set_$s_n" ] || "$SKINBAKE" export blender --bake "$tmpd/b_$s_n" \
		--out "$tmpd/set_$s_n" --mode exact >>"$tmpd/$s_n.log" 2>&1
	B --factory-startup --python "$imp" -- "$tmpd/set_$s_n" --mode "$s_mode" --scene sphere \
		--res 128 --samples "$s_spp" --save "$tmpd/$s_n-$s_mode.blend" >>"$tmpd/$s_n.log"
}
# ring NAME MODE SAMPLES RANGE [--ad]: measure-lights on the saved file, into $tmpd/r.log
ring() {
	B "$tmpd/$1-$2.blend" --python "$scn" -- measure-lights "$brdf" "$tmpd/b_$1" \
		"$tmpd/r_$1_$2" 128 "$3" "$4" $5 >"$tmpd/r.log" 2>&1
}
# mean_le N MEAN LIMIT / mean_gt: at least 200 pixels and the mean error at most / above LIMIT
mean_le() { awk -v n="$1" -v m="$2" -v l="$3" 'BEGIN { exit !(n >= 200 && m <= l) }'; }
mean_gt() { awk -v n="$1" -v m="$2" -v l="$3" 'BEGIN { exit !(n >= 200 && m > l) }'; }

set_up ad exact 4
check "default adding-doubling bake of paper, image set, exact sphere saved" \
	test -f "$tmpd/ad-exact.blend"
ring ad exact 4 70 --ad
set -- $(val SKINBAKE_LIGHTS "$tmpd/r.log")
check "exact mode, exit >= 70 deg, against adding-doubling: $1 px, mean $2, 95th pct $3, max $4" \
	mean_le "$1" "$2" 0.005
ring ad exact 4 70
set -- $(val SKINBAKE_LIGHTS "$tmpd/r.log")
ok "(for comparison) exact mode, exit >= 70 deg, against eval: $1 px, mean $2, max $4"

set_up nodes4 exact 4 --theta-nodes 4
ring nodes4 exact 4 70 --ad
set -- $(val SKINBAKE_LIGHTS "$tmpd/r.log")
check "the check can fail: a bake with --theta-nodes 4 is off there (mean $2 > 0.005)" \
	mean_gt "$1" "$2" 0.005

set_up ad general 64
ver=$(sed -n 's/^import_skin.py: .* in Blender \([0-9]*\)\..*/\1/p' "$tmpd/ad.log" | tail -1)
fit=general_fit
[ "${ver:-3}" -ge 4 ] && fit=general_fit_v4
lim=$(python3 -c "import json
print(*json.load(open('$tmpd/set_ad/manifest.json'))['$fit']['rms_error_uniform_rgb'])")
ring ad general 64 70 --ad
r=$(val SKINBAKE_RING "$tmpd/r.log")
check "general mode ($fit, Blender ${ver:-?}), exit >= 70 deg, render / AD: $r (1 +- $lim)" \
	python3 -c "
r, l = [float(x) for x in '$r'.split()], [float(x) for x in '$lim'.split()]
assert len(r) == 3 and all(abs(a - 1) <= b for a, b in zip(r, l))"
tap_done
