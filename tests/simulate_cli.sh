#!/bin/sh
# skinbake simulate: help text (every option with default, unit and range; the
# documented defaults are the real ones), --json output, exit status 2 with a
# message naming field, value and range for bad input.
. "$top_srcdir/tests/tap.sh"

src="$top_srcdir/src/cli/cmd_simulate.c"
# A cheap stack where roulette and multiple scattering both matter.
L="--layer d=0.05,mua=30,mus=90,g=0.75,n=1.4"

# Strict JSON (NaN and Infinity are not JSON) on stdin; prints nothing.
json_strict() {
	python3 -c '
import json, sys
def bad(c):
    raise ValueError("not JSON: " + c)
try:
    json.load(sys.stdin, parse_constant=bad)
except ValueError as e:
    sys.exit(str(e))'
}

# JSON of a run without the timing keys, for comparing runs.
norm() {
	python3 -c '
import json, sys
o = json.load(sys.stdin)
for k in ("seconds", "photons_per_second", "events_per_second"):
    o.pop(k, None)
print(json.dumps(o, sort_keys=True))'
}

# ---- help -----------------------------------------------------------------
if "$SKINBAKE" --help >"$tmpd/top.txt" 2>&1 && grep -q 'simulate' "$tmpd/top.txt"; then
	ok "skinbake --help exits 0 and lists simulate"
else
	fail "skinbake --help"
fi
if "$SKINBAKE" simulate --help >"$tmpd/help.txt" 2>"$tmpd/help.err" && [ -s "$tmpd/help.txt" ] && [ ! -s "$tmpd/help.err" ]; then
	ok "simulate --help exits 0 on stdout"
else
	fail "simulate --help"
fi

# The option names from the option table (entries with a destination,
# "{ "name", OPT_TYPE, &dest"), so that an option added to the table without
# documentation fails here.
grep -o '{ "[a-z][a-z-]*", OPT_[A-Z]*, &' "$src" |
	sed 's/{ "\([^"]*\)", OPT_\([A-Z]*\), &/\1 \2/; s/ FLAG$/ no/; s/ [A-Z]*$/ required/' >"$tmpd/opts.txt"
nopt=$(wc -l <"$tmpd/opts.txt")
if [ "$nopt" -ge 15 ]; then ok "found $nopt long options in $src"; else fail "found only $nopt long options in $src"; fi

# Paragraph of one option in the help: its line and the indented lines after it.
para() {
	awk -v o="--$1" '
		$1 == o || index($1, o "=") == 1 { on = 1; print; next }
		on && /^  --/ { exit }
		on && /^ *$/ { exit }
		on { print }' "$tmpd/help.txt"
}

while read -r name kind; do
	p=$(para "$name")
	if [ -z "$p" ]; then
		fail "--$name is in the getopt table but not in simulate --help"
		continue
	fi
	ok "--$name is documented"
	[ "$kind" = required ] || continue
	case $name in
	layer)
		# Per key: d, n, mua, mus, g with ranges, units and the defaults of n and g.
		p=$(echo "$p" | tr '\n' ' ' | tr -s ' ')
		if echo "$p" | grep -q ' d thickness .* in (0, inf) cm (required)' &&
		    echo "$p" | grep -q ' mua absorption coefficient in \[0, 1e8\] 1/cm (required)' &&
		    echo "$p" | grep -q ' mus scattering coefficient in \[0, 1e8\] 1/cm (required)' &&
		    echo "$p" | grep -q ' n refractive index in \[1, 10\] (default 1)' &&
		    echo "$p" | grep -q ' g Henyey-Greenstein anisotropy in (-1, 1) (default 0)'; then
			ok "--layer documents every key's range, unit and default"
		else
			fail "--layer help lacks a key's range, unit or default: $p"
		fi
		continue ;;
	esac
	if echo "$p" | grep -q '(default [^)]*)'; then ok "--$name shows its default"; else fail "--$name shows no default: $p"; fi
	# A range: an interval "[a, b]" / "(a, b]" ..., a list "a|b", or "must divide".
	if echo "$p" | grep -Eq '[[(][^])]*, *[^])]*[])]|[a-z]+\|[a-z]+|must divide'; then
		ok "--$name shows its range"
	else
		fail "--$name shows no range: $p"
	fi
done <"$tmpd/opts.txt"

# Units where the quantity has one.
for nu in "theta-in:) deg" "theta-out-step:] deg" "phi-step:] deg" "r-step:] cm"; do
	name=${nu%%:*} unit=${nu#*:}
	if para "$name" | grep -q "$unit"; then ok "--$name shows its unit ($unit)"; else fail "--$name lacks its unit $unit"; fi
done

# The documented defaults are the real ones: passing each default explicitly
# gives the same result bit for bit.  (Each option changes this stack's output
# when set otherwise, except --threads by design.  The step cap needs photons
# that walk long: a non-absorbing half space, where the cap ends ~0.2 %.)
S1="$L --photons 20000"
S2="--layer d=inf,mua=0,mus=100 --r-bins 0 --photons 2000"
"$SKINBAKE" simulate $S1 --json | norm >"$tmpd/base1.json"
"$SKINBAKE" simulate $S2 --json | norm >"$tmpd/base2.json"
while read -r name kind; do
	[ "$kind" = required ] || continue
	case $name in layer|photons) continue ;; esac
	def=$(para "$name" | tr '\n' ' ' | sed -n 's/.*[(;] *default \([^;)]*\)).*/\1/p')
	[ -n "$def" ] || continue
	if [ "$name" = max-steps ]; then S=$S2 base=base2; else S=$S1 base=base1; fi
	if "$SKINBAKE" simulate $S "--$name" "$def" --json 2>"$tmpd/def.err" | norm >"$tmpd/def.json" &&
	    cmp -s "$tmpd/$base.json" "$tmpd/def.json"; then
		ok "--$name $def (documented default) changes nothing"
	else
		fail "--$name $def (documented default) changes the result: $(cat "$tmpd/def.err")"
	fi
done <"$tmpd/opts.txt"
def=$(para photons | sed -n 's/.*(default \([^)]*\)).*/\1/p')
"$SKINBAKE" simulate --layer d=0.02,mua=10,mus=90,g=0.75 --json | norm >"$tmpd/p0.json"
"$SKINBAKE" simulate --layer d=0.02,mua=10,mus=90,g=0.75 --photons "$def" --json | norm >"$tmpd/p1.json"
check "--photons $def (documented default) changes nothing" cmp -s "$tmpd/p0.json" "$tmpd/p1.json"
"$SKINBAKE" simulate --layer d=0.05,mua=30,mus=90 --photons 20000 --json | norm >"$tmpd/k0.json"
"$SKINBAKE" simulate --layer d=0.05,mua=30,mus=90,n=1,g=0 --photons 20000 --json | norm >"$tmpd/k1.json"
check "--layer keys n and g default to 1 and 0" cmp -s "$tmpd/k0.json" "$tmpd/k1.json"

# ---- JSON output ----------------------------------------------------------
"$SKINBAKE" simulate --layer d=0.001,mua=0,mus=0,n=1.5 $L --layer d=inf,mua=7,mus=370,g=0.8,n=1.4 \
    --n-below 1.4 --theta-in 30 --photons 20000 --json >"$tmpd/out.json" 2>"$tmpd/out.err"
rc=$?
check "--json run exits 0" [ "$rc" -eq 0 ]
check "--json prints nothing on stderr (not a terminal)" [ ! -s "$tmpd/out.err" ]
check "--json output is strict JSON" json_strict <"$tmpd/out.json"
if python3 - "$tmpd/out.json" <<'EOF'
import json, math, sys
o = json.load(open(sys.argv[1]))
need = ["photons", "seconds", "Rsp", "Rd", "Rd_err", "Rd_unscattered", "Tt", "Tt_err", "A", "A_err", "lost", "brdf_az"]
miss = [k for k in need if k not in o]
miss += ["brdf_az." + k for k in ("theta_out_edges_deg", "fr", "fr_err") if k not in o.get("brdf_az", {})]
if miss:
    sys.exit("missing keys: " + ", ".join(miss))
b = o["brdf_az"]
assert o["photons"] == 20000, o["photons"]
assert len(o["A"]) == 3 and len(o["A_err"]) == 3, "A must have one entry per layer"
n = len(b["fr"])
assert n == 18 and len(b["fr_err"]) == n and len(b["theta_out_edges_deg"]) == n + 1
assert b["theta_out_edges_deg"][0] == 0 and b["theta_out_edges_deg"][-1] == 90
bal = o["Rsp"] + o["Rd"] + o["Tt"] + sum(o["A"]) + o["lost"] - 1
assert abs(bal) < 1e-9, "balance %g" % bal
assert o["A"][0] == 0, "the clear sebum layer absorbs nothing"
assert o["Tt"] == 0, "semi-infinite: nothing transmitted"
# The azimuth-averaged BRDF integrates (cos-weighted) to the scattered Rd.
e = [math.radians(x) for x in b["theta_out_edges_deg"]]
s = sum(f * math.pi * (math.sin(e[i + 1]) ** 2 - math.sin(e[i]) ** 2) for i, f in enumerate(b["fr"]))
assert abs(s - (o["Rd"] - o["Rd_unscattered"])) < 1e-9, "BRDF integral %g vs Rd %g" % (s, o["Rd"])
EOF
then ok "--json has every required key, consistent values"; else fail "--json keys or values"; fi

# One photon: errors are undefined, yet the output must stay valid JSON.
"$SKINBAKE" simulate $L --photons 1 --json >"$tmpd/one.json" 2>&1
check "--photons 1 --json is strict JSON (no NaN)" json_strict <"$tmpd/one.json"

# Same seed, any thread count: identical numbers.
"$SKINBAKE" simulate $L --photons 20000 --threads 1 --json | norm >"$tmpd/t1.json"
"$SKINBAKE" simulate $L --photons 20000 --threads 2 --json | norm >"$tmpd/t2.json"
check "--threads 1 and 2 give identical results" cmp -s "$tmpd/t1.json" "$tmpd/t2.json"
"$SKINBAKE" simulate $L --photons 20000 --seed 2 --json | norm >"$tmpd/s2.json"
check "another --seed gives other results" sh -c '! cmp -s "$1" "$2"' sh "$tmpd/t1.json" "$tmpd/s2.json"

# Table output.
if "$SKINBAKE" simulate $L --photons 2000 >"$tmpd/table.txt" 2>&1 &&
    grep -q '^  Rsp ' "$tmpd/table.txt" && grep -q '^  Rd ' "$tmpd/table.txt" && grep -q '^  Tt ' "$tmpd/table.txt" &&
    grep -q 'A layer 1' "$tmpd/table.txt" && grep -q 'lost' "$tmpd/table.txt"; then
	ok "table output lists Rsp, Rd, Tt, A, lost"
else
	fail "table output"
fi

# ---- bad input: exit 2, nothing on stdout, a message with field, value, range
# bad DESC "NEEDLE|NEEDLE|..." ARGS...: simulate ARGS refused (tests/lib/refused.sh): exit 2,
# nothing on stdout, every fixed-string NEEDLE in the message.
. "$top_srcdir/tests/lib/refused.sh"
refused_fixed=1 refused_quiet=1
bad() {
	b_d=$1 b_n=$2
	shift 2
	refused "$b_d" "$b_n" "" "$SKINBAKE" simulate "$@"
}

G="mua=1,mus=10"
bad "negative thickness" "--layer 1|d = -1|(0, inf)" --layer "d=-1,$G"
bad "NaN thickness" "--layer 1|d = 'nan'|(0, inf)" --layer "d=nan,$G"
bad "zero thickness" "--layer 1|d = 0|(0, inf)" --layer "d=0,$G"
bad "inf thickness above another layer" "--layer 1|d = inf|last layer" --layer "d=inf,$G" --layer "d=1,$G"
bad "g = 1" "--layer 1|g = 1|(-1, 1)" --layer "d=0.1,$G,g=1"
bad "g = 1.5" "--layer 2|g = 1.5|(-1, 1)" --layer "d=0.1,$G" --layer "d=0.1,$G,g=1.5"
bad "g = -1" "--layer 1|g = -1|(-1, 1)" --layer "d=0.1,$G,g=-1"
bad "n < 1" "--layer 1|n = 0.9|[1, 10]" --layer "d=0.1,$G,n=0.9"
bad "negative mua" "--layer 1|mua = -1|[0, 1e8]" --layer "d=0.1,mua=-1,mus=1"
bad "negative mus" "--layer 1|mus = -5|[0, 1e8]" --layer "d=0.1,mua=1,mus=-5"
bad "zero photons" "--photons|0|[1, " --layer "d=0.1,$G" --photons 0
bad "fractional photons" "--photons|1.5|[1, " --layer "d=0.1,$G" --photons 1.5
bad "unknown flag" "--bogus|--help" --layer "d=0.1,$G" --bogus
bad "missing option value" "--photons|--help" --layer "d=0.1,$G" --photons
bad "stray argument" "extra" --layer "d=0.1,$G" extra
bad "no layer" "--layer" --photons 10
bad "layer not key=value" "--layer 1|garbage|d, n, mua, mus, g" --layer garbage
bad "layer unknown key" "--layer 1|'x'|d, n, mua, mus, g" --layer "d=0.1,$G,x=3"
bad "layer missing key" "--layer 1|mus|d, mua, mus" --layer "d=0.1,mua=1"
bad "layer value not a number" "--layer 1|d|abc|(0, inf)" --layer "d=abc,$G"
bad "layer g not a number" "--layer 1|g|0.5x|(-1, 1)" --layer "d=0.1,$G,g=0.5x"
bad "layer empty value" "--layer 1|mua|[0, 1e8]" --layer "d=0.1,mua=,mus=1"
bad "17 layers" "--layer|16" $(for i in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17; do echo "--layer d=0.1,$G"; done)
bad "semi-infinite clear layer" "--layer 1|mua = mus = 0" --layer "d=inf,mua=0,mus=0"
bad "n-above < 1" "--n-above|0.5|[1, 10]" --layer "d=0.1,$G" --n-above 0.5
bad "n-below > 10" "--n-below|11|[1, 10]" --layer "d=0.1,$G" --n-below 11
bad "theta-in = 90" "--theta-in|90|[0, 90)" --layer "d=0.1,$G" --theta-in 90
bad "theta-in negative" "--theta-in|-5|[0, 90" --layer "d=0.1,$G" --theta-in -5
bad "unknown fresnel" "--fresnel|foo|exact, schlick" --layer "d=0.1,$G" --fresnel foo
bad "theta-out-step not dividing 90" "--theta-out-step|7|divide" --layer "d=0.1,$G" --theta-out-step 7
bad "batches 1" "--batches|1|[2, " --layer "d=0.1,$G" --batches 1
bad "roulette-chance 0" "--roulette-chance|0|(0, 1]" --layer "d=0.1,$G" --roulette-chance 0
bad "max-steps 0" "--max-steps|0|[1, " --layer "d=0.1,$G" --max-steps 0

tap_done
