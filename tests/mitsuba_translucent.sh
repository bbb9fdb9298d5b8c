#!/bin/sh
# The translucent mode in Mitsuba 3 (skinbake_mitsuba fit, transbsdf.py): a
# homogeneous medium per colour channel under the rough top, fitted to the
# bake's Rd(r), and the bake's table minus the medium's own BRDF on the surface.
#  - bad input: a bake without a radial profile, render without --fit (exit 2);
#  - the fit: the medium's power and mean radius within the bake's profile equal
#    the bake's (0.5 % and 1 %: the fit's bisection stops at 2e-4);
#  - a flat slab under a distant light, measured in Mitsuba, against skinbake
#    eval at four angle pairs where the remainder is not clipped: within 1 % plus
#    3 standard errors (the construction is exact up to the AD tables' 0.1 %, the
#    grid's 3e-4 and the two facet models);
#  - at grazing angles (light 0 / view 84, 80 / 80, 80 / 0 deg), where the medium under
#    the rough top returns up to 2.7 times the bake's light and the surface's grazing
#    weights (transbsdf.py) hold it back: against eval within 1 %, 3 standard errors,
#    the medium's table error times the weights and what the remainder still clips there;
#  - the profile measured in Mitsuba (ring emitter, measure.rd_ring) against the
#    bake's Rd(r): the power within 0.5 cm against the medium's (times the share
#    of its light the grazing weights let out) plus the remainder's albedo at
#    normal incidence (the remainder's light leaves where it enters), within 3
#    standard errors plus 3 %; the mean radius within 20 % of the
#    bake's (the remainder's local light pulls it in).
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/mitsuba_env.sh"
[ -n "$MTS_PY" ] || mts_skip_all

"$SKINBAKE" bake --preset paper --solver ad --quiet --out "$tmpd/bake" >/dev/null 2>&1 ||
	fail "bake paper"

# ---- bad input -------------------------------------------------------------------
mkdir "$tmpd/norad"
"$MTS_PY" - "$tmpd/bake/manifest.json" "$tmpd/norad/manifest.json" <<'PYEOF'
import json, sys
m = json.load(open(sys.argv[1]))
del m["radial"]
json.dump(m, open(sys.argv[2], "w"))
PYEOF
"$MTS_PY" -m skinbake_mitsuba fit --bake "$tmpd/norad" --out "$tmpd/f0" --skinbake "$SKINBAKE" \
	2>"$tmpd/e0"
rc=$?
if [ $rc -eq 2 ] && [ ! -e "$tmpd/f0" ] && grep -q "no radial profile (radial.rd_r)" "$tmpd/e0"
then
	ok "fit on a bake without Rd(r): exit 2 naming radial.rd_r, no output"
else
	fail "fit without radial: rc $rc, $(cat "$tmpd/e0")"
fi
"$MTS_PY" -m skinbake_mitsuba render "$tmpd" --mode translucent --out "$tmpd/x.exr" 2>"$tmpd/e1"
rc=$?
if [ $rc -eq 2 ] && [ ! -e "$tmpd/x.exr" ] && grep -q "needs --fit DIR" "$tmpd/e1"; then
	ok "render --mode translucent without --fit: exit 2"
else
	fail "render translucent without fit: rc $rc, $(cat "$tmpd/e1")"
fi

# ---- the fit ------------------------------------------------------------------------
if nice "$MTS_PY" -m skinbake_mitsuba fit --bake "$tmpd/bake" --out "$tmpd/fit" \
	--skinbake "$SKINBAKE" --photons 50000 2>"$tmpd/fit.err" && [ -f "$tmpd/fit/fit.json" ] &&
	[ -f "$tmpd/fit/medium/manifest.json" ]; then
	ok "fit: $(grep -c channel "$tmpd/fit.err") channels fitted, the medium baked"
else
	fail "fit: $(tail -3 "$tmpd/fit.err")"
fi

# ---- Mitsuba: flat slab and profile -----------------------------------------------
nice "$MTS_PY" - "$tmpd" "$SKINBAKE" >"$tmpd/res.txt" 2>"$tmpd/res.err" <<'PYEOF'
import json, math, subprocess, sys
import numpy as np
from skinbake_mitsuba import variant
variant.choose("mono")
from skinbake_mitsuba import transmeasure, transbsdf, tablegrid
d, skinbake = sys.argv[1], sys.argv[2]
bake, fitdir = d + "/bake", d + "/fit"
fit = json.load(open(fitdir + "/fit.json"))
for ch in fit["channels"]:
    dp = ch["medium_power"] / ch["bake_power"] - 1
    dm = ch["medium_mean_radius_cm"] / ch["bake_mean_radius_cm"] - 1
    good = abs(dp) < 0.005 and abs(dm) < 0.01
    print("%s|fit %s (%g nm): albedo %.4f, mu_t %.3g /cm; power %+.2f %%, mean radius %+.2f %% "
          "of the bake's" % ("ok" if good else "fail", ch["channel"], ch["wavelength_nm"],
                             ch["albedo"], ch["mu_t_per_cm"], 100 * dp, 100 * dm))
points = [(0, 30, 0), (30, 0, 0), (45, 30, 90), (20, 45, 180)]
grazing = [(0, 84, 0), (80, 80, 0), (80, 0, 0)]
gt = tablegrid.grid_theta()
gp = tablegrid.grid_phi()
edges = [0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5]
for c in range(3):
    k = fit["chan_wl"][c]
    name = "RGB"[c]
    res = transmeasure.flat(bake, fitdir, c, points, 4096, 4)
    for (ti, to, dph), (v, e) in zip(points, res):
        cmd = [skinbake, "eval", "--bake", bake, "--theta-in", str(ti), "--theta-out", str(to),
               "--phi", str(dph), "--json"]
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        ev = json.loads(out)["total"][k]
        dev = v / ev - 1
        tol = 0.01 + 3 * e / ev
        print("%s|flat %s, light %d, view %d, dphi %d: Mitsuba %.5f +- %.5f, eval %.5f: %+.2f %% "
              "(tolerance %.2f %%)" % ("ok" if abs(dev) <= tol else "fail", name, ti, to, dph, v, e,
                                      ev, 100 * dev, 100 * tol))
    # grazing: the medium's light through the surface's grazing weights c (transbsdf.py)
    # plus the remainder; expected eval plus what the remainder clips there, within 1 %,
    # 3 standard errors and the medium's table error (its bake's eval error times
    # c(theta_i) c(theta_o): where the remainder is not clipped the surface shows the
    # bake's BRDF plus c c (Mitsuba's medium - the medium's table))
    rem, bg, med, cw = transbsdf.remainder_grid(bake, fitdir + "/medium", k)
    raw = transbsdf.remainder_grid(bake, fitdir + "/medium", k, weights=False)[2]
    clipped = np.maximum(med - bg, 0.0)
    res = transmeasure.flat(bake, fitdir, c, grazing, 4096, 4)

    def node(g, ti, to, dph):
        """g at the grid node nearest to the point"""
        return float(g[np.abs(gt - math.radians(ti)).argmin(), np.abs(gt - math.radians(to)).argmin(),
                       np.abs(gp - math.radians(dph)).argmin()])

    def near(g, ti, to, dph):
        """the largest of g on the 8 grid nodes around the point"""
        ia = np.searchsorted(gt, math.radians(ti))
        ib = np.searchsorted(gt, math.radians(to))
        ic = np.searchsorted(gp, math.radians(dph))
        return float(g[max(ia - 1, 0):ia + 1, max(ib - 1, 0):ib + 1, max(ic - 1, 0):ic + 1].max())
    for (ti, to, dph), (v, e) in zip(grazing, res):
        cmd = [skinbake, "eval", "--bake", bake, "--theta-in", str(ti), "--theta-out", str(to),
               "--phi", str(dph), "--json"]
        ev = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)["total"][k]
        cmd[3] = fitdir + "/medium"
        merr = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)["diffuse_err"][k]
        cc = np.interp(math.radians(ti), gt, cw) * np.interp(math.radians(to), gt, cw)
        clip = near(clipped, ti, to, dph)
        dev = v / ev - 1
        tol = 0.01 + (3 * e + cc * merr + clip) / ev
        print("%s|grazing %s, light %d, view %d, dphi %d: Mitsuba %.5f +- %.5f, eval %.5f: %+.2f %% "
              "(tolerance %.2f %%: c c %.3f x the medium's table error %.5f, clipped %.5f); "
              "without the weights the medium's table alone is %.5f there"
              % ("ok" if abs(dev) <= tol else "fail", name, ti, to, dph, v, e, ev, 100 * dev,
                 100 * tol, cc, merr, clip, node(raw, ti, to, dph)))
    rings = transmeasure.rings(bake, fitdir, c, edges, 4096, 4)
    ref = transmeasure.bake_rings(bake, k, edges)
    p = sum(v for v, _ in rings)
    pe = math.sqrt(sum(e * e for _, e in rings))
    # the remainder's albedo at normal incidence (light leaving where it enters), and the
    # share of the medium's light its grazing weights let out
    row = rem[0]
    w = np.cos(gt) * np.sin(gt)
    a_rem = 2 * np.trapz(np.trapz(row, gp, axis=1) * w, gt)
    fexit = transbsdf.medium_exit_factor(raw, cw)
    expect = fit["channels"][c]["medium_power"] * fexit + a_rem
    mids = [0.5 * (a + b) for a, b in zip(edges, edges[1:])]
    mean = sum(m * v for m, (v, _) in zip(mids, rings)) / p
    mean_b = sum(m * v for m, v in zip(mids, ref)) / sum(ref)
    dev = p / expect - 1
    tol = 0.03 + 3 * pe / expect
    print("%s|profile %s: power within 0.5 cm %.4f +- %.4f, expected %.4f (medium %.4f x %.3f let out + "
          "remainder %.4f; bake %.4f): %+.1f %% (tolerance %.1f %%)"
          % ("ok" if abs(dev) <= tol else "fail", name, p, pe, expect,
             fit["channels"][c]["medium_power"], fexit, a_rem, sum(ref), 100 * dev, 100 * tol))
    dmean = mean / mean_b - 1
    ratios = " ".join("%.2f" % (v / b) for (v, _), b in zip(rings, ref))
    print("%s|profile %s: mean radius (ring midpoints) %.4f cm, bake %.4f cm: %+.1f %%; "
          "rings Mitsuba / bake: %s" % ("ok" if abs(dmean) <= 0.2 else "fail", name, mean, mean_b,
                                        100 * dmean, ratios))
PYEOF
py_rc=$?
[ -s "$tmpd/res.txt" ] || fail "measurements: $(tail -5 "$tmpd/res.err")"
while IFS='|' read -r verdict text; do
	if [ "$verdict" = ok ]; then ok "$text"; else fail "$text"; fi
done <"$tmpd/res.txt"
# a measurement that stopped half-way is a failure, not a shorter plan
[ "$py_rc" -eq 0 ] || fail "the measurements stopped (exit $py_rc): $(tail -3 "$tmpd/res.err" | tr '\n' ' ')"
tap_done
