#!/bin/sh
# Silhouettes of Mitsuba 3 renders against adding-doubling itself (issue 26 item 4; the
# POV-Ray and Blender twins are tests/pov_silhouette.sh and tests/blender_silhouette.sh):
# a default adding-doubling bake of `paper` (9 x 9), the same sphere scene
# (scenes/sphere.scene: unit sphere, one parallel light, orthographic, 128 x 128) exported
# by `skinbake export mitsuba` and rendered by `python -m skinbake_mitsuba render` in table
# mode (llvm_ad_rgb, box-filtered pixels, independent sampler) at MTS_SEEDS seeds of MTS_SPP
# samples per pixel.  The expected pixel is the pixel mean of E cos(theta_i) f, f from
# adding-doubling point values of the bake's own layer stacks (tests/blender_brdf --ad over
# tests/ad_points.c, not eval, which the table BSDF resamples by construction), by 3 x 3
# Gauss-Legendre points per pixel (tests/lib/ortho_sphere.py; its error against 6 x 6:
# 1.2e-5 mean), on the pixels wholly on the sphere and lit whose centre's exit angle is
# 70 deg or more (about 560 px, 70 to 82 deg exit, 24 to 88 deg incidence).
# The error of a pixel is its relative error, the largest over R, G, B; the test is the mean
# of that over the ring, as the other two.  The bound: 0.5 % (the other renderers' bound,
# table against adding-doubling) plus the noise's share: sqrt(2/pi) s + 3 s / sqrt(N), s the
# RMS over the ring of the per-pixel relative standard error of the seeds' mean (from the
# seed-to-seed spread; the noise of R, G and B is correlated to 0.999, so a pixel's largest
# is about one channel's), N the pixels; the expected mean |noise| and 3 of its standard
# deviations.  A bake with --theta-nodes 4 (linear in theta_i between 0, 22.5, 45 and
# 67.5 deg) must fail the same check.  About 40 s of CPU.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/mitsuba_env.sh"
[ -n "$MTS_PY" ] || mts_skip_all
: "${MTS_SEEDS:=4}" "${MTS_SPP:=512}"
BRDF="$top_builddir/tests/blender_brdf"
SC="$top_srcdir/scenes/sphere.scene"
LIB="$top_srcdir/tests/lib"

# bake NAME ARGS...: a paper bake as the other silhouette tests make it, exported for Mitsuba
bake() {
	b_n=$1
	shift
	"$SKINBAKE" bake --preset paper --out "$tmpd/b_$b_n" --resolution 9x9 --r-bins 20 \
		--radial-photons 4000 --quiet "$@" >"$tmpd/$b_n.log" 2>&1 &&
		"$SKINBAKE" export mitsuba --scene "$SC" --bake "$tmpd/b_$b_n" --mode table \
			--out "$tmpd/e_$b_n" >>"$tmpd/$b_n.log" 2>&1
}
# render NAME: MTS_SEEDS renders of the export, seeds 1..MTS_SEEDS
render() {
	r_s=1
	while [ $r_s -le "$MTS_SEEDS" ]; do
		nice "$MTS_PY" -m skinbake_mitsuba render "$tmpd/e_$1" --mode table --spp "$MTS_SPP" \
			--seed $r_s --out "$tmpd/r_$1_$r_s.exr" >>"$tmpd/$1.log" 2>&1 || return 1
		r_s=$((r_s + 1))
	done
}
# ring NAME [--ad-ref]: the comparison (tests/lib/ortho_sphere.py), one line of numbers:
# pixels, mean error, bound, 95th percentile, max, s, mean signed error (R G B) and its error
ring() {
	"$MTS_PY" - "$LIB" "$tmpd" "$1" "$MTS_SEEDS" "$BRDF" "$2" <<'PYEOF'
import os, subprocess, sys
import numpy as np
lib, d, name, seeds, brdf, how = sys.argv[1:7]
sys.path.insert(0, lib)
import ortho_sphere as osp
import mitsuba as mi
mi.set_variant("scalar_rgb")
v = osp.View(os.path.join(d, "e_" + name, "scene.json"))
rows, cols = v.ring(70.0)
quad, wts = v.quadrature(rows, cols, 3)
# the expected pixel means: adding-doubling (the bake's stacks; "ad", cached per stack in
# ref.npy: a bake of the same preset has the same stacks) or eval ("eval", for comparison)
cache = os.path.join(d, "ref.npy")
if how == "ad" and os.path.exists(cache):
    ref = np.load(cache)
else:
    ref = 0.0
    for ti, to, ph, ci, e in quad:
        inp = "".join("%.9g %.9g %.9g\n" % t for t in zip(ti.ravel(), to.ravel(), ph.ravel()))
        out = subprocess.run([brdf, os.path.join(d, "b_" + name)] + (["--ad"] if how == "ad" else []),
                             input=inp, capture_output=True, text=True, check=True).stdout
        f = np.array(out.split(), dtype=float).reshape(ti.shape + (3,))
        ref = ref + np.einsum("pk,pkc->pc", wts[None, :] * ci, f) * e
    if how == "ad":
        np.save(cache, ref)
px = np.stack([np.array(mi.Bitmap(os.path.join(d, "r_%s_%d.exr" % (name, s))))[rows, cols, :3]
               for s in range(1, int(seeds) + 1)]).astype(float)
k = px.shape[0]
m = px.mean(axis=0)
se = px.std(axis=0, ddof=1) / np.sqrt(k) / ref          # relative standard error per pixel, channel
e = m / ref - 1.0
err = np.abs(e).max(axis=1)
n = len(err)
s = float(np.sqrt((se.max(axis=1) ** 2).mean()))
bound = 0.005 + np.sqrt(2.0 / np.pi) * s + 3.0 * s / np.sqrt(n)
bias_err = float(np.sqrt((se ** 2).sum(axis=0).max())) / n
print(n, "%.5f %.5f %.5f %.5f %.5f" % (err.mean(), bound, np.percentile(err, 95), err.max(), s),
      "%+.5f %+.5f %+.5f %.5f" % tuple(list(e.mean(axis=0)) + [bias_err]),
      "%.1f %.1f" % (quad[0][1][:, 4].min(), quad[0][1][:, 4].max()),
      "%.1f %.1f" % (quad[0][0][:, 4].min(), quad[0][0][:, 4].max()))
PYEOF
}
pct() { awk -v x="$1" 'BEGIN { printf "%.3f %%", 100 * x }'; }
# le N MEAN BOUND / gt: at least 200 pixels and the mean at most / above the bound
le() { awk -v n="$1" -v m="$2" -v b="$3" 'BEGIN { exit !(n >= 200 && m <= b) }'; }
gt() { awk -v n="$1" -v m="$2" -v b="$3" 'BEGIN { exit !(n >= 200 && m > b) }'; }

check "default adding-doubling bake of paper (9 x 9), sphere scene exported for Mitsuba" bake ad
check "the bake holds point values" "$MTS_PY" -c "
import json; m=json.load(open('$tmpd/b_ad/manifest.json')); assert m['table']['values']==['points']*3"
render ad
check "Mitsuba renders it: $MTS_SEEDS seeds x $MTS_SPP spp (the last: $(tail -1 "$tmpd/ad.log" | sed 's/^skinbake_mitsuba render: //'))" \
	test $? -eq 0
set -- $(ring ad ad)
if [ $# -eq 14 ]; then
	check "exit ${11}-${12} deg (incidence ${13}-${14}), against adding-doubling point values: $1 px, mean $(pct "$2"), 95th pct $(pct "$4"), max $(pct "$5") (<= $(pct "$3"): 0.5 % plus the noise's share; per-pixel standard error $(pct "$6") RMS)" \
		le "$1" "$2" "$3"
	ok "mean signed error R $(pct "$7"), G $(pct "$8"), B $(pct "$9") (+- $(pct "${10}"), the noise's standard error)"
else
	fail "the comparison against adding-doubling printed: $*"
fi
set -- $(ring ad eval)
ok "(for comparison) the same pixels against eval: mean $(pct "$2"), max $(pct "$5"), signed R $(pct "$7")"

check "a bake with --theta-nodes 4 of the same stacks, exported" bake nodes4 --theta-nodes 4
check "the two bakes have the same layer stacks (the adding-doubling values are reused)" "$MTS_PY" -c "
import json; a, b = (json.load(open('$tmpd/b_%s/manifest.json' % n))['layers'] for n in ('ad', 'nodes4'))
assert a == b"
check "Mitsuba renders it ($MTS_SEEDS x $MTS_SPP spp)" render nodes4
set -- $(ring nodes4 ad)
check "the check can fail: the --theta-nodes 4 bake is off there: mean $(pct "$2") > $(pct "$3") ($1 px)" gt "$1" "$2" "$3"
tap_done
