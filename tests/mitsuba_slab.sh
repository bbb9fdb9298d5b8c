#!/bin/sh
# Volumetric Mitsuba 3 (exporters/mitsuba, skinbake_mitsuba slab) against skinbake
# simulate on a flat three-layer slab: Rd at 0/45/75 deg and azimuthal BRDF
# bands against adding-doubling, Rd(r) rings against Monte Carlo, within 3
# combined standard errors; the mean exit radius within 10 %. A low-albedo stack
# (short paths) keeps the Mitsuba run near a minute on 2 cores.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/mitsuba_env.sh"
[ -n "$MTS_PY" ] || mts_skip_all

S1="d=0.001,n=1.5,mua=0,mus=0"
S2="d=0.01,n=1.4,mua=4,mus=150,g=0.8"
S3="d=0.25,n=1.4,mua=8,mus=150,g=0.8"
RINGS="0,0.02,0.05,0.1,0.2,0.5"

# ---- bad input: message naming the value, exit 2, nothing on stdout ---------
"$MTS_PY" -m skinbake_mitsuba slab --layer "d=0.01,n=1.4,mua=4,mus=150,g=1.5" >"$tmpd/bad.out" 2>"$tmpd/bad.err"
rc=$?
if [ $rc -eq 2 ] && [ ! -s "$tmpd/bad.out" ] && grep -q 'g=1.5 is outside (-1, 1)' "$tmpd/bad.err"; then
	ok "slab --layer g=1.5: exit 2 naming g, the value and the range"
else
	fail "slab --layer g=1.5: rc $rc, $(cat "$tmpd/bad.err")"
fi
"$MTS_PY" -m skinbake_mitsuba slab --layer "$S2" --band 30,20,40 >"$tmpd/bad.out" 2>"$tmpd/bad.err"
rc=$?
if [ $rc -eq 2 ] && [ ! -s "$tmpd/bad.out" ] && grep -q 'view outside the band' "$tmpd/bad.err"; then
	ok "slab --band holding the mirror direction: exit 2"
else
	fail "slab --band 30,20,40: rc $rc, $(cat "$tmpd/bad.err")"
fi

# ---- references ----------------------------------------------------------------
L="--layer $S1 --layer $S2 --layer $S3"
for t in 0 45 75 10 30 60; do
	"$SKINBAKE" simulate $L --solver ad --theta-in $t --json >"$tmpd/ad$t.json" || fail "simulate ad $t"
done
"$SKINBAKE" simulate $L --photons 1e6 --r-step 0.01 --r-bins 50 --json >"$tmpd/mc.json" || fail "simulate mc"

# ---- Mitsuba ------------------------------------------------------------------
if nice "$MTS_PY" -m skinbake_mitsuba slab $L --theta-in 0,45,75 --rings "$RINGS" \
	--band 10,50,70 --band 30,45,65 --band 60,5,25 --spp 8192 --batches 8 \
	>"$tmpd/mts.json" 2>"$tmpd/mts.err"; then
	ok "skinbake_mitsuba slab runs ($(sed -n 's/.*"variant": "\([a-z_]*\)".*"seconds": \([0-9.]*\).*/\1, \2 s/p' "$tmpd/mts.json"))"
else
	fail "skinbake_mitsuba slab: $(tail -3 "$tmpd/mts.err")"
	tap_done
	exit 1
fi

"$MTS_PY" - "$tmpd" >"$tmpd/cmp.txt" <<'PYEOF'
import json, math, sys
d = sys.argv[1]
m = json.load(open(d + "/mts.json"))
ad = {t: json.load(open("%s/ad%s.json" % (d, t))) for t in (0, 45, 75, 10, 30, 60)}
mc = json.load(open(d + "/mc.json"))

def tap(good, text):
    print(("ok" if good else "fail") + "|" + text)

for e in m["rd"]:
    a = ad[int(e["theta_in_deg"])]
    s = math.hypot(e["Rd_err"], a["Rd_err"])
    z = (e["Rd"] - a["Rd"]) / s
    tap(abs(z) <= 3.0 and abs(e["Rsp"] - a["Rsp"]) < 1e-9,
        "Rd at %g deg: mitsuba %.5f +- %.5f, adding-doubling %.5f (%.2f sigma); Rsp %.6f = %.6f"
        % (e["theta_in_deg"], e["Rd"], e["Rd_err"], a["Rd"], z, e["Rsp"], a["Rsp"]))

# Azimuthal BRDF over a polar band = the projected-solid-angle mean of the
# adding-doubling bands inside it, for incidence along the view (reciprocity).
for e in m["brdf"]:
    az = ad[int(e["theta_view_deg"])]["brdf_az"]
    edges = az["theta_out_edges_deg"]
    num = var = den = 0.0
    for k in range(len(edges) - 1):
        if edges[k] >= e["theta_lo_deg"] - 1e-9 and edges[k + 1] <= e["theta_hi_deg"] + 1e-9:
            w = math.sin(math.radians(edges[k + 1])) ** 2 - math.sin(math.radians(edges[k])) ** 2
            num += w * az["fr"][k]
            var += (w * az["fr_err"][k]) ** 2
            den += w
    ref = num / den
    s = math.hypot(e["fr_err"], math.sqrt(var) / den)
    z = (e["fr"] - ref) / s
    tap(abs(z) <= 3.0, "BRDF view %g deg, light %g-%g deg: mitsuba %.5f +- %.5f /sr, adding-doubling %.5f (%.2f sigma)"
        % (e["theta_view_deg"], e["theta_lo_deg"], e["theta_hi_deg"], e["fr"], e["fr_err"], ref, z))

rr = mc["Rd_r"]
edges = rr["r_edges_cm"]
def mc_ring(r0, r1):
    v = var = 0.0
    for k in range(len(edges) - 1):
        if edges[k] >= r0 - 1e-12 and edges[k + 1] <= r1 + 1e-12:
            area = math.pi * (edges[k + 1] ** 2 - edges[k] ** 2)
            v += rr["rd_per_cm2"][k] * area
            var += (rr["rd_err"][k] * area) ** 2
    return v, math.sqrt(var)

def rbar(r0, r1):
    return 2.0 / 3.0 * (r1 ** 3 - r0 ** 3) / (r1 ** 2 - r0 ** 2)

sm = sw = rm = rw = 0.0
for e in m["rings"]:
    r0, r1 = e["r0_cm"], e["r1_cm"]
    v, ve = mc_ring(r0, r1)
    s = math.hypot(e["power_err"], ve)
    z = (e["power"] - v) / s
    tap(abs(z) <= 3.0, "Rd(r) ring %g-%g cm: mitsuba %.5f +- %.5f, Monte Carlo %.5f +- %.5f (%.2f sigma)"
        % (r0, r1, e["power"], e["power_err"], v, ve, z))
    sm += e["power"] * rbar(r0, r1)
    sw += e["power"]
    rm += v * rbar(r0, r1)
    rw += v
mean_m = sm / sw
mean_r = rm / rw
tap(abs(mean_m / mean_r - 1.0) <= 0.10, "mean exit radius within 0.5 cm: mitsuba %.4f cm, Monte Carlo %.4f cm (%+.1f %%)"
    % (mean_m, mean_r, 100.0 * (mean_m / mean_r - 1.0)))
PYEOF
[ -s "$tmpd/cmp.txt" ] || fail "the comparison printed nothing"
while IFS='|' read -r verdict text; do
	if [ "$verdict" = ok ]; then ok "$text"; else fail "$text"; fi
done <"$tmpd/cmp.txt"
tap_done
