#!/bin/sh
# skinbake bake and eval from the command line: documented files, readable by
# exrheader, eval answers in JSON; bad input exits 2 and writes nothing.
# (tests/solver_cli.sh has the adding-doubling bakes.)
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"
B="$SKINBAKE"
out="$tmpd/bake"
check "bake paper (small, Monte Carlo)" "$B" bake --preset paper --solver mc --out "$out" --theta-in 0,30.0,60 \
	--resolution 6x6 --target-error 0.1 --batch-photons 500 --quiet
for f in brdf.exr brdf_rgb.exr albedo.exr albedo.png manifest.json; do
	check "bake wrote $f" [ -s "$out/$f" ]
done
if command -v exrheader >/dev/null 2>&1; then
	check "exrheader reads brdf.exr with its channels" sh -c "exrheader '$out/brdf.exr' | grep -q 'fr_err.550nm'"
	check "exrheader reads brdf_rgb.exr" sh -c "exrheader '$out/brdf_rgb.exr' | grep -q 'skinbake:axes'"
else
	fail "exrheader is missing (package openexr)"
fi
check "manifest states error reached, photons, time" python3 -c "
import json,sys; m=json.load(open('$out/manifest.json'))
r=m['result']; assert r['rms_rel_err']<=0.1 and r['photons']>0 and r['seconds']>0 and r['target_met']
assert m['wavelengths_nm']==[470,550,656] and len(m['theta_i_deg'])==3 and len(m['layers'])==3
assert len(m['radial']['mean_radius_cm'])==3 and m['settings']['seed']==1"
"$B" eval --bake "$out" --theta-in 30 --theta-out 20 --phi 180 --json > "$tmpd/eval.json"
check "eval --json has the documented keys" python3 -c "
import json; d=json.load(open('$tmpd/eval.json'))
for k in ('wavelengths_nm','diffuse','diffuse_err','specular','total'): assert len(d[k])==3, k
assert all(abs(t-(a+b))<1e-12 for t,a,b in zip(d['total'],d['diffuse'],d['specular']))
assert all(x>0 for x in d['diffuse'])"
check "eval table output" sh -c "'$B' eval --bake '$out' --theta-in 10 --theta-out 10 --phi 0 | grep -q 'linear sRGB'"

# Bad input: exit 2, a message naming the option/value/range, no output.
bad() {	# DESC PATTERN ARGS...: skinbake ARGS refused (tests/lib/refused.sh)
	b_d=$1 b_p=$2
	shift 2
	refused "$b_d" "$b_p" "$tmpd/bad" "$B" "$@"
}
bad "unknown preset" "very-fair-oily" bake --preset nope --out "$tmpd/bad"
bad "missing preset file" "nofile.ini" bake --preset-file "$tmpd/nofile.ini" --out "$tmpd/bad"
bad "wavelength out of range" "\[380, 780\]" bake --preset fair-oily --wavelengths 300 --out "$tmpd/bad"
bad "paper at an untabulated wavelength" "470" bake --preset paper --wavelengths 500 --out "$tmpd/bad"
bad "theta-in 90" "\[0, 90)" bake --preset paper --theta-in 90.0 --out "$tmpd/bad"
bad "target error too small" "\[0.001, 1\]" bake --preset paper --target-error 0.0001 --out "$tmpd/bad"
bad "bad resolution" "\[1, 360\]" bake --preset paper --resolution 0x5 --out "$tmpd/bad"
bad "unknown flag" "unknown" bake --preset paper --frobnicate --out "$tmpd/bad"
bad "no --out" "--out" bake --preset paper
bad "estimator" "nee, bins" bake --preset paper --estimator magic --out "$tmpd/bad"
bad "eval on a missing bake" "No such file or directory" eval --bake "$tmpd/bad" --theta-in 1 --theta-out 1 --phi 1
bad "eval angle out of range" "\[0, 90\]" eval --bake "$out" --theta-in 95 --theta-out 1 --phi 1
echo "{" > "$tmpd/corrupt.json"; mkdir -p "$tmpd/corrupt"; cp "$tmpd/corrupt.json" "$tmpd/corrupt/manifest.json"
bad "eval on a corrupt manifest" "corrupt" eval --bake "$tmpd/corrupt" --theta-in 1 --theta-out 1 --phi 1
check "bake --help lists every option" sh -c "for o in preset preset-file out wavelengths spectral theta-in resolution solver ad-tol ad-quad radial-photons target-error max-photons batch-photons r-step r-bins fresnel estimator seed threads quiet; do '$B' bake --help | grep -q -- \"--\$o\" || exit 1; done"
tap_done
