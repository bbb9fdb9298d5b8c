#!/bin/sh
# The mm-scale relief ([surface] macro_slope, engine/macro.h; issue 21 round
# 4) from the command line: the key's range (exit 2, no output), the resolved
# preset text, a small Monte Carlo bake with and without it (same seed: the
# tables hold the same values, the relief is applied where the BRDF is
# evaluated), m -> 0 gives the flat bake's eval, the manifest records it and
# a bad value there is refused, eval sees it, and the POV-Ray exporter (which
# reads through export/source.h) writes a different table for it.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"

bad() {
	printf '%b' "$2" >"$tmpd/$1.ini"
	refused_quiet=1
	refused "$1: exit 2, '$3'" "$3" "" "$SKINBAKE" preset show --preset-file "$tmpd/$1.ini"
}
bad negative '[skin]\nbase = fair-dry\n[surface]\nmacro_slope = -0.1\n' 'surface.macro_slope = -0.1: out of range \[0, 0.8\]'
bad above '[skin]\nbase = fair-dry\n[surface]\nmacro_slope = 0.81\n' 'surface.macro_slope = 0.81: out of range'

"$SKINBAKE" preset show fair-oily --ini | grep -q 'macro_slope' && fail "flat preset text has macro_slope" \
	|| ok "flat preset text unchanged (no macro_slope key)"
printf '[skin]\nbase = fair-oily\n[surface]\nmacro_slope = 0.2\n' >"$tmpd/m.ini"
"$SKINBAKE" preset show --preset-file "$tmpd/m.ini" --ini | grep -q '^macro_slope = 0.2$' \
	&& ok "macro_slope in the resolved text" || fail "macro_slope in the resolved text"
printf '[skin]\nbase = fair-oily\n[surface]\nmacro_slope = 0.0001\n' >"$tmpd/m0.ini"

# The same Monte Carlo bake three times (seed 1): flat, m = 1e-4, m = 0.2.
bk() {
	"$SKINBAKE" bake $1 --solver mc --out "$tmpd/$2" --theta-in 0,20,40,60,75,85 --resolution 9x6 --wavelengths 550 \
		--target-error 0.3 --batch-photons 500 --seed 1 --threads 1 --quiet 2>"$tmpd/err-$2"
}
if bk "--preset fair-oily" flat && bk "--preset-file $tmpd/m0.ini" m0 && bk "--preset-file $tmpd/m.ini" m; then
	ok "three small bakes"
else
	fail "bakes: $(cat "$tmpd"/err-*)"
fi
python3 -c "
import json, sys
a = json.load(open('$tmpd/flat/manifest.json'))['specular']; b = json.load(open('$tmpd/m/manifest.json'))['specular']
sys.exit(0 if 'macro_slope' not in a and abs(b['macro_slope'] - 0.2) < 1e-12 and 'macro' in b else 1)" \
	&& ok "manifest: specular.macro_slope recorded (absent when flat)" || fail "manifest macro_slope"

# eval: total at a few geometries; m = 1e-4 within 1e-4 relative of flat
# (the change is O(m^2) away from grazing; measured 1.4e-5 at 20/30/0);
# m = 0.2 differs by more than 2 %.  Not at theta_i = 0: there the local
# azimuth of a tilted facet is any, and a Monte Carlo table's azimuth bins
# at normal incidence differ by their noise (4.7e-4 of the total at 0/30/0).
ev() { "$SKINBAKE" eval --bake "$tmpd/$1" --theta-in "$2" --theta-out "$3" --phi "$4" --json | python3 -c "
import json, sys; print(json.load(sys.stdin)['total'][0])"; }
worst=0 moved=0
for g in "5 30 0" "30 30 180" "45 60 90" "60 70 150" "70 20 30"; do
	set -- $g
	f=$(ev flat "$@") z=$(ev m0 "$@") m=$(ev m "$@")
	worst=$(python3 -c "print(max($worst, abs($z - $f) / $f))")
	moved=$(python3 -c "print(max($moved, abs($m - $f) / $f))")
done
python3 -c "import sys; sys.exit(0 if $worst < 1e-4 else 1)" && ok "m = 1e-4: eval within 1e-4 of the flat bake ($worst)" \
	|| fail "m = 1e-4: eval off the flat bake by $worst"
python3 -c "import sys; sys.exit(0 if $moved > 0.02 else 1)" && ok "m = 0.2: eval moves (largest change $moved)" \
	|| fail "m = 0.2: eval did not move ($moved)"

# A bad value in a manifest is refused at load (eval exit 2).
sed 's/"macro_slope": *[0-9.e+-]*/"macro_slope":1.5/' "$tmpd/m/manifest.json" >"$tmpd/mf.json"
if grep -q '"macro_slope":1.5' "$tmpd/mf.json"; then
	mkdir -p "$tmpd/mbad" && cp "$tmpd"/m/* "$tmpd/mbad/" && cp "$tmpd/mf.json" "$tmpd/mbad/manifest.json"
	"$SKINBAKE" eval --bake "$tmpd/mbad" --theta-in 0 --theta-out 30 --phi 0 >/dev/null 2>"$tmpd/err"
	rc=$?
	[ $rc -ne 0 ] && grep -q 'macro_slope\|checksum\|manifest' "$tmpd/err" && ok "bad macro_slope in a manifest: refused (exit $rc)" \
		|| fail "bad macro_slope in a manifest: exit $rc, $(cat "$tmpd/err")"
else
	fail "manifest text not as expected (no macro_slope to change)"
fi

# The POV-Ray exporter tabulates through export/source.h: its data differ with the relief.
# (The relief costs the exporters 512 evaluations of the table per value: a
# full 65 x 65 x 17 POV-Ray table took 15 s of CPU against 0.2 s flat.)
pov() {
	"$SKINBAKE" export pov --bake "$tmpd/$1" --light type=point,position=2:1.5:-2.5,name=key --nodes 9 --gamma-nodes 3 \
		--camera type=perspective,location=0:0:-3,angle=40 --out "$tmpd/pov-$1" 2>>"$tmpd/err"
}
if pov flat && pov m; then
	cmp -s "$tmpd/pov-flat/skin.inc" "$tmpd/pov-m/skin.inc" && fail "export pov: same skin.inc with the relief" \
		|| ok "export pov: the relief reaches the exported data"
else
	fail "export pov: $(cat "$tmpd/err")"
fi
tap_done
