#!/bin/sh
# Translucent skin, steps 1-2 (issue 27): each renderer's own subsurface
# closure (POV-Ray 3.7's translucency, Cycles' random walk in Debian's
# Blender), fitted by export/sss_fit to a bake's Rd(r) from the committed
# calibration (tests/data/sss_calib/RENDERER.json, sss_table.c), rendered by
# the real renderer on a thick slab and its profile read back
# (scripts/sss_profile.py: shadowed rings of a parallel light, a fisheye at
# the unlit centre, every exit direction).  For paper, fair-dry and dark-dry
# (adding-doubling tables, Monte Carlo Rd(r) at 1 %), per channel, within the
# bake's profile (5 mm): the power within 2 %, the mean radius within 10 %,
# the RMS of ln(R_render / R_bake) over the rings holding 95 % of the power
# within 0.25 (the material: the closure and, where the fit leaves part of
# the power to the table at the entry point, a Lambertian of that albedo;
# where the fit itself predicts more than 0.25 from the
# closure's measured shape, the check is a TAP TODO: one closure cannot
# follow that profile, docs/translucency.md).  A bake without a radial profile and a renderer without a
# calibration exit 2 with a message.  About 20 small renders per preset and
# renderer (POV-Ray about 1 s each, Cycles at 32 samples 2 s).  Cycles also in
# each bpy venv of $BPY_PYTHONS (4.5 LTS, 5.0: "Random Walk (Skin)", their own
# calibrations tests/data/sss_calib/cycles-M.N.json) through tests/bpy-blender, at 128 samples
# (at 32 the small blue and green powers of paper came out 2.1 % off in one version or the other:
# noise, every ring rendered with the same seed).
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
FIT="$top_builddir/tests/sss_fit_print"
PROF="$top_srcdir/scripts/sss_profile.py"
if [ -z "$POVRAY" ] || ! command -v "$POVRAY" >/dev/null 2>&1 || ! command -v python3 >/dev/null 2>&1 ||
    [ -z "$BLENDER" ] || ! command -v "$BLENDER" >/dev/null 2>&1; then
	fail "povray, blender or python3 is missing (POVRAY='$POVRAY' BLENDER='$BLENDER'): the set-up installs them"
	tap_done
	exit 1
fi

# Known limits are todo lines (tests/tap.sh): a run that meets one reports a plain pass, not an
# unexpected one: these limits sit within the bake's noise of the bound, so an XPASS would make
# the suite fail at random.
for p in paper fair-dry dark-dry; do
	# --radial-error 0.01: the bake's rings about as precise as before the control-variate
	# estimator (speed3: 2 % on the mean radius leaves single rings 1.5-2x noisier), so the
	# checks measure the renderer's closure rather than the bake's ring noise.
	"$B" bake --preset "$p" --radial-error 0.01 --out "$tmpd/$p" --quiet >"$tmpd/bake.log" 2>&1
	check "$p: bake" test $? -eq 0
done
runs="pov cycles"
for py in $BPY_PYTHONS; do
	[ -x "$py" ] || continue
	v=$(timeout 120 "$py" -c "import bpy; print('V %d.%d' % tuple(bpy.app.version[:2]))" \
		2>/dev/null | sed -n 's/^V //p')
	[ -n "$v" ] || continue
	if ! "$FIT" "cycles-$v" "$tmpd/paper" >/dev/null 2>&1; then
		skip "bpy $v: no calibrated subsurface closure for this Cycles (translucent mode refuses it)"
		continue
	fi
	runs="$runs cycles-$v"
	eval "bpy_$(echo "$v" | tr . _)=\$py"
done
# SSS_PROFILE_RUNS="cycles-4.5 ..." renders only those (while developing).
runs=${SSS_PROFILE_RUNS:-$runs}
for r in $runs; do
samples=800
prof=$r bl=$BLENDER bpy=${BPY_PYTHON:-} method=random_walk
case $r in
cycles) samples=32 ;;
cycles-*) samples=128 prof=cycles bl="$top_srcdir/tests/bpy-blender" method=random_walk_skin
	eval "bpy=\$bpy_$(echo "${r#cycles-}" | tr . _)" ;;
esac
for p in paper fair-dry dark-dry; do
	scale=1
	[ $r = pov ] && scale=0.999	# the exporter's layering shows POV-Ray's closure at 0.999
	"$FIT" $r "$tmpd/$p" $scale >"$tmpd/$p.fit" 2>"$tmpd/fit.log"
	check "$r $p: fit of the closure" test $? -eq 0
	# Render the fitted closure on the bake's rings.
	args=$(python3 -c 'import json,sys; f=json.load(open(sys.argv[1]))
print("--colour " + ",".join("%.6g" % x for x in f["colour"]) + " --radius " + ",".join("%.6g" % x for x in f["length_mm"])
      + " --local " + ",".join("%.6g" % x for x in f["local"])
      + " --edges " + ",".join("%.6g" % r[0] for r in f["bake_rings"]) + ",%.6g" % f["bake_rings"][-1][1])' "$tmpd/$p.fit")
	# shellcheck disable=SC2086
	BLENDER="$bl" BPY_PYTHON="$bpy" python3 "$PROF" $prof $args --method $method \
		--samples $samples --json "$tmpd/$p.prof" 2>"$tmpd/prof.log"
	check "$r $p: the renderer renders the fitted slab" test -s "$tmpd/$p.prof"
	python3 - "$tmpd/$p.fit" "$tmpd/$p.prof" >"$tmpd/cmp.txt" <<'PY'
import json, math, sys
f = json.load(open(sys.argv[1]))
m = json.load(open(sys.argv[2]))
rings = f["bake_rings"]
cen = [2.0 / 3.0 * (b ** 3 - a ** 3) / (b * b - a * a) for a, b, *_ in rings]
for c, name in enumerate("RGB"):
    pb = [r[2 + c] for r in rings]
    pm = [r[c] for r in m["ring_power"]]
    ib, im = sum(pb), sum(pm)
    mb = sum(p * x for p, x in zip(pb, cen)) / ib
    mm = sum(p * x for p, x in zip(pm, cen)) / im
    cum, s, n = 0.0, 0.0, 0
    for a, b in zip(pb, pm):
        if a > 0 and b > 0:
            s += math.log(b / a) ** 2
            n += 1
        cum += a
        if cum >= 0.95 * ib:
            break
    rms = math.sqrt(s / n)
    print(f"{name} {im / ib - 1:.4f} {mm / mb - 1:.4f} {rms:.4f} {ib:.5g} {mb:.4g} {f['rms_log'][c]:.4f}")
PY
	while read -r ch di dm rms ib mb pred; do
		echo "# $r $p $ch: power $ib (render/bake - 1 = $di), mean radius $mb mm ($dm), RMS ln $rms (predicted $pred)"
		check "$r $p $ch: power within 2 % ($di)" python3 -c "import sys; sys.exit(abs($di) > 0.02)"
		check "$r $p $ch: mean radius within 10 % ($dm)" python3 -c "import sys; sys.exit(abs($dm) > 0.10)"
		if python3 -c "import sys; sys.exit($pred <= 0.25)"; then
			todo "$r $p $ch: RMS of ln R(r) within 0.25 ($rms)" "the closure's own shape: predicted $pred" \
				python3 -c "import sys; sys.exit($rms > 0.25)"
		elif [ "$r $p $ch" = "pov paper B" ]; then
			# Known limit, not the fit's: the best closure over colour, length and local part
			# (scripts/sss_fit_search.py) predicts 0.2513 and POV-Ray's render adds 0.04-0.06
			# (docs/translucency.md); the prediction itself moves 0.24-0.25 with the bake's noise.
			todo "$r $p $ch: RMS of ln R(r) within 0.25 ($rms)" "the closure's best shape 0.2513" \
				python3 -c "import sys; sys.exit($rms > 0.25)"
		else
			check "$r $p $ch: RMS of ln R(r) within 0.25 ($rms)" python3 -c "import sys; sys.exit($rms > 0.25)"
		fi
	done <"$tmpd/cmp.txt"
done
done

# Bad input: no radial profile; a renderer without calibration.
cp -r "$tmpd/paper" "$tmpd/norad"
python3 -c 'import json,sys; p=sys.argv[1]; m=json.load(open(p)); del m["radial"]["rd_r"]; json.dump(m, open(p, "w"))' \
	"$tmpd/norad/manifest.json"
"$FIT" pov "$tmpd/norad" >/dev/null 2>"$tmpd/e.log"
rc=$?
check "a bake without a radial profile: exit 2 naming radial.rd_r" test $rc -eq 2
check "  ... and the message says so" grep -q "radial.rd_r" "$tmpd/e.log"
"$FIT" mitsuba "$tmpd/paper" >/dev/null 2>"$tmpd/e.log"
check "a renderer without a calibration: exit 2" test $? -eq 2
tap_done
