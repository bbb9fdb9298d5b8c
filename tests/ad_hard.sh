#!/bin/sh
# The hard cases of issue 13 through the command line, as a user meets them:
# `skinbake simulate --solver ad --json` at its default tolerance (1e-4) on
# optical thickness 1e4, a half space of albedo 0.9999, grazing incidence
# (89 deg), index jumps 1.0 -> 2.0, 16 layers, a 1e-7 cm layer and clear
# films only.  Each must finish (exit 0), balance energy
# (Rsp + Rd + Tt + sum A = 1 to 1e-6) and state an honest error:
#   - against a solve at twice the nodes per unit cosine (--ad-quad) to
#     --ad-tol 1e-6 (so more Fourier orders; tests/test_ad.c compares 16
#     with 48 nodes on the same cases through the library):
#     |X - X_ref| <= err + err_ref for Rd, Tt and each A, and for every
#     azimuthal band of the BRDF; the table's actual RMS relative difference
#     <= its rms_rel_err + the reference's;
#   - where Monte Carlo is cheap (about 1e5 photons), against `simulate`
#     by Monte Carlo with fixed seeds: Rd and Tt within 3 sigma (the AD
#     error added to the MC standard error), Rsp to 1e-12.
# Peaked phase functions, g = +-0.99, are where adding-doubling is weak:
# at simulate's default tolerance (1e-4) it must refuse (exit 2, the cause on stderr,
# nothing on stdout); at --ad-tol 0.1 it must either solve with an error
# estimate that covers the difference from Monte Carlo (g = 0.99) or refuse
# (g = -0.99); and `bake --solver auto` must fall back to Monte Carlo for
# that wavelength and say so on stderr.
# Issue 26: at the bake's default tolerance (0.001) a g = 0.99 layer and a
# layer of optical thickness 1e-3 are solved (see below).
# Cost: about 55 s of CPU (the g = +-0.99 refusals search up to 256 nodes
# per unit cosine, about 3 s each; the Monte Carlo runs 1-2 s each, the
# two fallback bakes about 3 s each, the two solves at 0.001 5 and 2 s).
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
CHK="$tmpd/chk.py"
cat >"$CHK" <<'PY'
import json, math, sys
mode = sys.argv[1]
a = json.load(open(sys.argv[2]))
def bal(x):
    return abs(x['Rsp'] + x['Rd'] + x['Tt'] + sum(x['A']) - 1.0)
if mode == 'balance':
    assert bal(a) < 1e-6 and abs(a['balance']) < 1e-6, (bal(a), a['balance'])
elif mode == 'ref':	# honest against a higher-order solve
    b = json.load(open(sys.argv[3]))
    # the whole table (bins theta_o-major): solid-angle-weighted RMS relative difference
    t = [math.radians(x) for x in a['brdf']['theta_out_edges_deg']]
    fx, fy = a['brdf']['fr'], b['brdf']['fr']
    npb = len(fx) // (len(t) - 1)
    num = den = 0.0
    for i, (x, y) in enumerate(zip(fx, fy)):
        if y > 0:
            w = math.cos(t[i // npb]) - math.cos(t[i // npb + 1])
            num += w * ((x - y) / y) ** 2; den += w
    act = math.sqrt(num / den) if den else 0.0
    print('# n_quad %d vs %d, orders %d vs %d, Rd %.8g +- %.1e (ref %.8g), Tt %.6g +- %.1e (ref %.6g), table RMS'
          ' estimated %.1e actual %.1e' % (a['n_quad'], b['n_quad'], a['fourier_orders'], b['fourier_orders'],
          a['Rd'], a['Rd_err'], b['Rd'], a['Tt'], a['Tt_err'], b['Tt'], a['rms_rel_err'], act))
    assert 2 * a['n_quad'] == b['n_quad'] and a['tol'] > b['tol']
    assert act <= a['rms_rel_err'] + b['rms_rel_err'] + 1e-15, ('table', act, a['rms_rel_err'])
    for k in ('Rd', 'Tt'):
        d = abs(a[k] - b[k])
        assert d <= a[k + '_err'] + b[k + '_err'] + 1e-15, (k, a[k], b[k], d, a[k + '_err'])
    for x, y, ex, ey in zip(a['A'], b['A'], a['A_err'], b['A_err']):
        assert abs(x - y) <= ex + ey + 1e-15, ('A', x, y, ex)
    fa, fb = a['brdf_az'], b['brdf_az']
    for x, y, ex, ey in zip(fa['fr'], fb['fr'], fa['fr_err'], fb['fr_err']):
        assert abs(x - y) <= ex + ey + 1e-15, ('band', x, y, ex, ey)
elif mode == 'mc':	# against Monte Carlo
    m = json.load(open(sys.argv[3]))
    assert abs(a['Rsp'] - m['Rsp']) < 1e-12, (a['Rsp'], m['Rsp'])
    for k in ('Rd', 'Tt'):
        s = math.hypot(m[k + '_err'], a[k + '_err'])
        d = abs(a[k] - m[k])
        print('# %s AD %.6g MC %.6g +- %.2g (%.1f sigma)' % (k, a[k], m[k], m[k + '_err'], d / s if s else 0))
        assert d <= 3 * s + 1e-12, (k, a[k], m[k], s)
PY
PYC() { python3 "$CHK" "$@"; }

# hard NAME MC_PHOTONS SIMULATE-ARGS...: the checks above (MC_PHOTONS 0: no
# Monte Carlo).
hard() {
	h_name=$1 h_mc=$2; shift 2
	"$B" simulate "$@" --solver ad --json >"$tmpd/ad.json" 2>"$tmpd/ad.err"
	h_rc=$?
	check "$h_name: simulate --solver ad finishes (exit $h_rc)" [ "$h_rc" = 0 ]
	[ "$h_rc" = 0 ] || { sed 's/^/# /' "$tmpd/ad.err"; return; }
	check "$h_name: Rsp + Rd + Tt + sum A = 1 to 1e-6" PYC balance "$tmpd/ad.json"
	h_q=$(python3 -c "import json; print(2 * json.load(open('$tmpd/ad.json'))['n_quad'])")
	"$B" simulate "$@" --solver ad --ad-quad "$h_q" --ad-tol 1e-6 --json >"$tmpd/ref.json" 2>"$tmpd/ref.err" ||
		sed 's/^/# /' "$tmpd/ref.err"
	check "$h_name: error estimates cover the difference from 2x the nodes and --ad-tol 1e-6" \
		PYC ref "$tmpd/ad.json" "$tmpd/ref.json"
	if [ "$h_mc" != 0 ]; then
		"$B" simulate "$@" --photons "$h_mc" --seed 7 --r-bins 0 --json >"$tmpd/mc.json" 2>"$tmpd/mc.err"
		check "$h_name: agrees with Monte Carlo ($h_mc photons)" PYC mc "$tmpd/ad.json" "$tmpd/mc.json"
	fi
}

SKIN="--layer d=0.001,n=1.5,mua=0,mus=0 --layer d=0.01,n=1.4,mua=50,mus=370,g=0.8 --layer d=0.25,n=1.4,mua=7,mus=370,g=0.8 --n-below 1.4"
L16=
i=0
while [ $i -lt 16 ]; do
	L16="$L16 --layer d=0.00$((3 + i % 7)),n=1.3$((3 + i % 5)),mua=$((1 + i)),mus=$((200 + 10 * i)),g=0.$((70 + i))"
	i=$((i + 1))
done
# shellcheck disable=SC2086
{
hard "optical thickness 1e4" 0 --layer d=10,n=1.4,mua=10,mus=990,g=0.8 --n-below 1.4 --theta-in 34
hard "half space, albedo 0.9999" 0 --layer d=inf,n=1.4,mua=0.01,mus=99.99,g=0.8 --theta-in 34
hard "skin stack at 89 deg" 200000 $SKIN --theta-in 89
hard "index 2.0 slab in air" 100000 --layer d=0.05,n=2.0,mua=2,mus=100,g=0.8 --theta-in 60
hard "index 1.0 over 2.0" 100000 --layer d=0.01,n=1.0,mua=2,mus=100,g=0.8 --layer d=0.05,n=2.0,mua=2,mus=100,g=0.8 --theta-in 34
hard "16 layers" 100000 $L16 --n-below 1.38 --theta-in 34
hard "a 1e-7 cm layer" 100000 --layer d=1e-7,n=1.4,mua=50,mus=400,g=0.8 --layer d=0.01,n=1.3,mua=50,mus=370,g=0.8 \
	--layer d=0.2,n=1.45,mua=7,mus=370,g=0.8 --n-below 1.4 --theta-in 34
}

# Clear films only: nothing scatters, Rsp + Tt = 1 exactly, as the Monte
# Carlo's launch.
CLEAR="--layer d=0.001,n=1.5,mua=0,mus=0 --layer d=3,n=1.4,mua=0,mus=0 --n-below 1.33 --theta-in 40"
# shellcheck disable=SC2086
"$B" simulate $CLEAR --solver ad --json >"$tmpd/ad.json"
rc=$?
# shellcheck disable=SC2086
"$B" simulate $CLEAR --photons 1000 --r-bins 0 --json >"$tmpd/mc.json"
check "clear films only: finishes ($rc), Rd = 0, Rsp + Tt = 1, Rsp as Monte Carlo's" python3 -c "
import json; a=json.load(open('$tmpd/ad.json')); m=json.load(open('$tmpd/mc.json'))
assert a['Rd']==0 and all(x==0 for x in a['brdf_az']['fr']) and abs(a['Rsp']+a['Tt']-1)<1e-15
assert abs(a['Rsp']-m['Rsp'])<1e-15 and abs(a['Tt']-m['Tt'])<1e-12 and a['Rsp']>0.04"

# Issue 26: a g = 0.99 layer and a thin layer (optical thickness 1e-3) are solved by
# adding-doubling at the bake's default tolerance (`bake --help`'s --ad-tol default, 0.001;
# simulate's own default is 1e-4), at normal incidence: the node search escalates to 256 nodes
# per unit cosine (measured: 6.1e-4 and 6.8e-4 estimated, 8 s and 3 s) instead of refusing;
# balance to 1e-6, the estimate within the tolerance, Rd and Tt within 3 sigma of Monte Carlo
# (1e6 photons).  (A skin stack with g = 0.99 in both scattering layers is still refused at
# 0.001: 0.0073 at 256 nodes; docs/grazing.md.)
tol=$("$B" bake --help | sed -n '/^  --ad-tol E/,/default/p' | sed -n 's/.*(default \([0-9.e-]*\)).*/\1/p')
check "bake's default --ad-tol is 0.001 ($tol)" [ "$tol" = 0.001 ]
for L in "g = 0.99 layer|d=0.1,n=1.4,mua=1,mus=100,g=0.99" "tau 1e-3 layer|d=0.0000099,n=1.4,mua=1,mus=100,g=0.8"
do
	name=${L%%|*}
	"$B" simulate --layer "${L#*|}" --theta-in 0 --solver ad --ad-tol "$tol" --json >"$tmpd/ad.json" \
		2>"$tmpd/e"
	rc=$?
	check "$name: solved at the bake's default tolerance $tol (exit $rc$(sed 's/^/: /' "$tmpd/e"))" \
		python3 -c "
import json; a=json.load(open('$tmpd/ad.json')); print('# n_quad', a['n_quad'], 'rms', a['rms_rel_err'])
assert a['tol'] == $tol and 0 < a['rms_rel_err'] <= a['tol']"
	check "$name: balances" PYC balance "$tmpd/ad.json"
	"$B" simulate --layer "${L#*|}" --theta-in 0 --photons 1000000 --seed 7 --r-bins 0 --json \
		>"$tmpd/mc.json"
	check "$name: agrees with Monte Carlo (1e6 photons)" PYC mc "$tmpd/ad.json" "$tmpd/mc.json"
done

# g = +-0.99: refused at the default tolerance; g = 0.99 solved at --ad-tol
# 0.1 with an error estimate that covers Monte Carlo (1e6 photons: at 1e5
# the MC error, 0.8% of Rd, is larger than what is tested); g = -0.99 is
# refused even at 0.1, the loosest tolerance (the estimate grows with the
# nodes: backward peaks the quadrature does not resolve).  Either way
# `bake --solver auto` falls back to Monte Carlo for that wavelength.
for g in 0.99 -0.99; do
	G="--layer d=0.1,n=1.4,mua=1,mus=100,g=$g --theta-in 34"
	# shellcheck disable=SC2086
	"$B" simulate $G --solver ad --json >"$tmpd/o" 2>"$tmpd/e"
	rc=$?
	check "g = $g: --solver ad refuses the default tolerance (exit $rc), says why, prints nothing" sh -c \
		"[ $rc = 2 ] && grep -q 'adding-doubling cannot meet the tolerance' '$tmpd/e' && [ ! -s '$tmpd/o' ]"
	# shellcheck disable=SC2086
	"$B" simulate $G --solver ad --ad-tol 0.1 --json >"$tmpd/ad.json" 2>"$tmpd/e"
	rc=$?
	# Both solved since the search escalates to 256 nodes before refusing
	# (issue 26; g = -0.99 was refused before): checked against Monte Carlo.
	check "g = $g: --ad-tol 0.1 finishes ($rc) and balances" PYC balance "$tmpd/ad.json"
	# shellcheck disable=SC2086
	"$B" simulate $G --photons 1000000 --seed 7 --r-bins 0 --json >"$tmpd/mc.json"
	check "g = $g: --ad-tol 0.1 agrees with Monte Carlo within its error" PYC mc "$tmpd/ad.json" "$tmpd/mc.json"
	printf '[skin]\nbase = paper\nname = peaked\n[override.550]\nepidermis.g = %s\ndermis.g = %s\n' "$g" "$g" \
		>"$tmpd/g.ini"
	# --ad-quad-max 64 bounds the search's cost (a table solve at 256 nodes and
	# all Fourier orders of g = 0.99 takes minutes); the escalation itself is
	# tested through simulate above and in tests/test_ad.
	"$B" bake --preset-file "$tmpd/g.ini" --theta-in 30 --resolution 6x4 --r-bins 20 --radial-error 0.2 \
		--target-error 0.2 --estimator bins --ad-quad-max 64 --out "$tmpd/bake$g" --quiet >"$tmpd/o" 2>"$tmpd/e"
	rc=$?
	check "g = $g: bake --solver auto falls back to Monte Carlo at 550 nm and says so (exit $rc)" sh -c \
		"[ $rc = 0 ] && grep -q '^skinbake bake: adding-doubling cannot solve 550 nm (.*); Monte Carlo instead' '$tmpd/e'"
	check "g = $g: the manifest records the fallback" python3 -c "
import json; m=json.load(open('$tmpd/bake$g/manifest.json')); s=m['solver']
assert s['name']=='ad+mc' and [f['wavelength_nm'] for f in s['fallback_to_mc']]==[550]
assert [j['solver'] for j in m['jobs']]==['ad','mc','ad']"
done
tap_done
