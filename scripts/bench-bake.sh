#!/bin/sh
# Bake benchmarks: time to 1% RMS error, error against photons against an
# independent reference (table and plot), efficiency of next-event estimation
# and of the roulette settings, cost against resolution, wavelengths and
# incidence angles, thread speedup.  Prints one markdown section; plots go to
# $BENCH_OUT (default docs/bench).  BENCH_QUICK=1 shrinks every photon count
# (for trying the script; its numbers are not the benchmark).
set -eu
SKINBAKE=${SKINBAKE:-./skinbake}
top_srcdir=${top_srcdir:-.}
OUT=${BENCH_OUT:-$top_srcdir/docs/bench}
QUICK=${BENCH_QUICK:-0}
mkdir -p "$OUT"
W=$(mktemp -d "${TMPDIR:-/tmp}/skinbake-bench-bake.XXXXXX")
trap 'rm -rf "$W"' EXIT INT TERM

if [ "$QUICK" = 1 ]; then
	TARGET=0.03		# error of the timed target bakes
	TOPT="--batch-photons 500 "	# their first round is 8 batches per job
	REF_N=480000 REF_B=2000	# reference bake photons, batch photons
	CURVE="24000:100 96000:400 240000:1000"	# photons:batch-photons
	NEE_N=96000 NEE_B=400 BINS_N=960000	# nee against bins (same bake)
	THR_N=96000 THR_B=400	# thread speedup
	SIM_N=2e5		# roulette settings (simulate)
	PJ=8000 PJ_B=1000	# photons per job of the cost sweeps, batch photons
	RES="9x9 18x18 36x36"
	FULL_N=240000 FULL_B=1000	# full bake of the one-light comparison
else
	TARGET=0.01
	TOPT=
	REF_N=4800000 REF_B=4000
	CURVE="24000:100 96000:400 288000:1200 960000:4000 2880000:12000"
	NEE_N=288000 NEE_B=1200 BINS_N=2880000
	THR_N=288000 THR_B=1200
	SIM_N=1e6
	PJ=32000 PJ_B=4000
	RES="9x9 18x18 36x36 72x72"
	FULL_N=960000 FULL_B=4000
fi

# Helpers: run a command and record wall and CPU seconds; read a bake's
# manifest and tables (scripts/bench_tables.py, tests/lib/images.py).
cat > "$W/bb.py" <<'EOF'
import json, math, os, resource, subprocess, sys, time
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "scripts"))
from bench_tables import manifest, table  # one reader of bakes and OpenEXR (tests/lib/images.py)

def rms(f, e, w):
    return math.sqrt(sum(wi * ((ei / fi) if fi > 0 else 1.0) ** 2 for fi, ei, wi in zip(f, e, w)) / sum(w))

cmd = sys.argv[1]
if cmd == 'run':	# run LOG CMD...: print "wall cpu" seconds
    r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
    with open(sys.argv[2], 'w') as log:
        rc = subprocess.call(sys.argv[3:], stdout=log, stderr=subprocess.STDOUT)
    t1, r1 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
    if rc != 0:
        sys.stderr.write(open(sys.argv[2]).read())
        sys.exit(rc)
    print('%.3f %.3f' % (t1 - t0, r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime))
elif cmd == 'info':	# info DIR: photons, bake seconds, RMS relative error, jobs
    r = manifest(sys.argv[2])
    print(r['result']['photons'], '%.3f' % r['result']['seconds'], '%.6g' % r['result']['rms_rel_err'], len(r['jobs']))
elif cmd == 'cmp':	# cmp DIR REF: RMS relative difference, reference's own RMS, own RMS from the table
    f, e, w = table(sys.argv[2])
    g, ge, gw = table(sys.argv[3])
    keep = [i for i in range(len(g)) if g[i] > 0]
    sw = sum(w[i] for i in keep)
    d = math.sqrt(sum(w[i] * ((f[i] - g[i]) / g[i]) ** 2 for i in keep) / sw)
    er = math.sqrt(sum(w[i] * (ge[i] / g[i]) ** 2 for i in keep) / sw)
    print('%.6g %.6g %.6g %d' % (d, er, rms(f, e, w), len(g) - len(keep)))
elif cmd == 'sim':	# sim JSON: photons, seconds, Rd, Rd_err, RMS relative error of the theta_o bands
    d = json.load(open(sys.argv[2]))
    b = d['brdf_az']
    r = math.sqrt(sum(((e / f) if f > 0 else 1.0) ** 2 for f, e in zip(b['fr'], b['fr_err'])) / len(b['fr']))
    print(d['photons'], '%.3f' % d['seconds'], '%.6f' % d['Rd'], '%.4g' % d['Rd_err'], '%.4g' % r,
          '%.1f' % (d['scattering_events'] / d['photons']))
EOF
PY() { top_srcdir="$top_srcdir" python3 "$W/bb.py" "$@"; }
calc() { awk "BEGIN { printf \"$1\n\", $2 }"; }
# bake NAME ARGS...: run `skinbake bake --solver mc ARGS --out $W/NAME --quiet`
# (this section measures the Monte Carlo bake; the default solver is
# adding-doubling since issue 13, scripts/bench-solvers.sh); sets
# wall cpu photons secs err jobs (and b_*; sh has no local variables).
bake() {
	b_name=$1; shift
	b_run=$(PY run "$W/$b_name.log" "$SKINBAKE" bake --solver mc "$@" --out "$W/$b_name" --quiet)
	b_info=$(PY info "$W/$b_name")
	# shellcheck disable=SC2086
	set -- $b_run $b_info
	wall=$1 cpu=$2 photons=$3 secs=$4 err=$5 jobs=$6
}
load() { sed 's/.*load average: //' /proc/loadavg 2>/dev/null | cut -d' ' -f1-3 || uptime; }

cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')
t_start=$(date +%s)
echo "## Bake"
echo
echo "Machine: $cpu, $(nproc) cores; $(date -u +%Y-%m-%d); load average at the start"
echo "$(load) (1, 5, 15 min). Command: \`make bench\` (scripts/bench-bake.sh)."
if [ "$QUICK" = 1 ]; then
	echo
	echo "**BENCH_QUICK=1: reduced photon counts and target $TARGET; not the benchmark.**"
fi
echo
echo "Every bake below is the Monte Carlo bake, \`skinbake bake --solver mc --preset ... --out DIR\` with the options shown"
echo "(default: all cores, 18 x 18 table, 10 incidence angles, the preset's wavelengths, seed 1,"
echo "batches of 4000 photons). \"seconds\" is the bake's own compute time (manifest \`result.seconds\`);"
echo "\"wall\" is the whole command (start-up and writing included); \"CPU\" is user + system time."
echo "\"RMS error\" is the bake's solid-angle-weighted RMS relative standard error of the table."

# The reference for every error comparison: another seed, many photons.
ref_cmd="skinbake bake --solver mc --preset refstack --target-error 0 --max-photons $REF_N --batch-photons $REF_B --seed 2 --out REF"
bake ref --preset refstack --target-error 0 --max-photons "$REF_N" --batch-photons "$REF_B" --seed 2
ref_err=$err ref_photons=$photons ref_secs=$secs

# --- Targets ---------------------------------------------------------------
echo
echo "### Targets: \`refstack\` to ${TARGET} RMS relative error"
echo
echo "| bake | command | photons | seconds | wall | CPU | RMS error | against reference (d / predicted) | target |"
echo "|---|---|---|---|---|---|---|---|---|"
# shellcheck disable=SC2086
bake full --preset refstack --target-error "$TARGET" $TOPT
met=$(awk "BEGIN { print ($wall < 60) ? \"met\" : \"NOT met\" }")
# shellcheck disable=SC2046
set -- $(PY cmp "$W/full" "$W/ref")
vsref="$1 ($(calc '%.2f' "$1 / sqrt($err * $err + $2 * $2)"))"
echo "| refstack, 3 wavelengths x 10 angles, 18 x 18 | \`skinbake bake --solver mc --preset refstack --target-error $TARGET ${TOPT}--out DIR\` | $photons | $secs | $wall | $cpu | $err | $vsref | under 60 s wall: $met |"
# shellcheck disable=SC2086
bake one --preset refstack --target-error "$TARGET" --theta-in 30.0 $TOPT
echo "| one light (30 deg), 3 wavelengths, 18 x 18 | \`skinbake bake --solver mc --preset refstack --target-error $TARGET --theta-in 30.0 ${TOPT}--out DIR\` | $photons | $secs | $wall | $cpu | $err | - | - |"
echo
echo "\"against reference\" and \"d / predicted\": see the next section (1 when the reported error is right)."
echo
echo "Thread speedup on the same work (\`refstack\`, fixed photons, identical output):"
echo
echo "| threads | command | photons | seconds | wall | CPU | speedup |"
echo "|---|---|---|---|---|---|---|"
bake thr1 --preset refstack --target-error 0 --max-photons "$THR_N" --batch-photons "$THR_B" --threads 1
s1=$secs c1=$cpu
echo "| 1 | \`skinbake bake --solver mc --preset refstack --target-error 0 --max-photons $THR_N --batch-photons $THR_B --threads 1 --out DIR\` | $photons | $secs | $wall | $cpu | 1 |"
bake thr2 --preset refstack --target-error 0 --max-photons "$THR_N" --batch-photons "$THR_B" --threads 2
same=$(cmp -s "$W/thr1/brdf.exr" "$W/thr2/brdf.exr" && echo "tables identical" || echo "TABLES DIFFER")
echo "| 2 | \`skinbake bake --solver mc --preset refstack --target-error 0 --max-photons $THR_N --batch-photons $THR_B --threads 2 --out DIR\` | $photons | $secs | $wall | $cpu | $(calc '%.2f' "$s1 / $secs") (target >= 1.8; $same) |"
echo
echo "CPU time with two threads over one thread: $(calc '%.3f' "$cpu / $c1") (1 = no parallel overhead; a"
echo "speedup below 2 with this near 1 means the cores were shared with other work)."

# --- Error against photons ---------------------------------------------------
echo
echo "### \`refstack\`: error against photons"
echo
echo "Reference: the independent bake above, \`$ref_cmd\`"
echo "($ref_photons photons, $ref_secs s, its own RMS error $ref_err). Each row is"
echo "\`skinbake bake --solver mc --preset refstack --target-error 0 --max-photons N --batch-photons B --out DIR\` (seed 1;"
echo "B = N / 240 gives 8 batches for each of the 30 jobs). \"against reference\" is the"
echo "solid-angle-weighted RMS of (f - f_ref) / f_ref over all bins; it contains the reference's own"
echo "error, so the next column removes it (sqrt(d^2 - e_ref^2)); the last column is d over the"
echo "value the two reported errors predict, sqrt(e^2 + e_ref^2) (1 when the reported errors are right)."
echo
echo "| photons | batch photons | seconds | wall | reported RMS error | against reference | reference error removed | d / predicted |"
echo "|---|---|---|---|---|---|---|---|"
: > "$W/conv.dat"
for nb in $CURVE; do
	n=${nb%:*} b=${nb#*:}
	bake "c$n" --preset refstack --target-error 0 --max-photons "$n" --batch-photons "$b"
	# shellcheck disable=SC2046
	set -- $(PY cmp "$W/c$n" "$W/ref")
	d=$1 er=$2
	corr=$(calc '%.4g' "($d * $d > $er * $er) ? sqrt($d * $d - $er * $er) : 0")
	pred=$(calc '%.2f' "$d / sqrt($err * $err + $er * $er)")
	echo "| $photons | $b | $secs | $wall | $err | $d | $corr | $pred |"
	echo "$photons $secs $err $d $corr" >> "$W/conv.dat"
	echo "$cpu" > "$W/c$n.cpu"
	if [ "$n" = "$NEE_N" ]; then cp -r "$W/c$n" "$W/nee"; fi
	if [ "$n" = "$FULL_N" ]; then cp -r "$W/c$n" "$W/fullfix"; fi
done
echo
# shellcheck disable=SC2046
set -- $(tail -1 "$W/conv.dat")
echo "The series stops at $1 photons ($2 s), the cap that keeps this benchmark to a few minutes:"
echo "at that rate 1e8 photons would take about $(calc '%.0f' "$2 * 1e8 / $1 / 60") minutes."
if command -v gnuplot >/dev/null 2>&1; then
	cp "$W/conv.dat" "$OUT/bake_error.dat"
	gnuplot <<GP
set terminal pngcairo size 640,440
set output "$OUT/bake_error_vs_time.png"
set termoption noenhanced
set logscale xy
set xlabel "bake seconds ($(nproc) threads)"
set ylabel "RMS relative error of the table"
set key top right
set title "refstack bake (3 wavelengths x 10 angles, 18 x 18): error against time"
last = system("tail -1 $OUT/bake_error.dat | cut -d' ' -f2") + 0
laste = system("tail -1 $OUT/bake_error.dat | cut -d' ' -f3") + 0
plot "$OUT/bake_error.dat" using 2:3 with linespoints pt 5 title "reported by the bake", \
     "$OUT/bake_error.dat" using 2:4 with points pt 7 title "against the seed-2 reference", \
     "$OUT/bake_error.dat" using 2:5 with points pt 6 title "against the reference, its error removed", \
     laste*sqrt(last/x) with lines dt 2 title "1/sqrt(N) guide"
GP
	rm -f "$OUT/bake_error.dat"
	echo
	echo "![bake error against time](docs/bench/bake_error_vs_time.png)"
fi

# --- Efficiency ----------------------------------------------------------------
echo
echo "### Efficiency of the variance reduction"
echo
echo "Efficiency = 1 / (variance x time), with variance = (RMS relative error)^2 and time = the"
echo "bake's (or simulation's) own seconds; the gain is the ratio to the plain MCML-style setting."
echo "Next-event estimation against binning the escaping photons, on the same bake (\`refstack\`,"
echo "3 wavelengths x 10 angles, 18 x 18; binning gets 10 times the photons so that few bins stay"
echo "empty: an empty bin counts as 100% error):"
echo
echo "| estimator | command | photons | seconds | CPU | RMS error | efficiency [1/s] | gain | gain by CPU time |"
echo "|---|---|---|---|---|---|---|---|---|"
# shellcheck disable=SC2046
set -- $(PY info "$W/nee") $(cat "$W/c$NEE_N.cpu")
photons=$1 secs=$2 err=$3 cpu=$5
eff_nee=$(calc '%.4g' "1 / ($err * $err * $secs)") effc_nee=$(calc '%.6g' "1 / ($err * $err * $cpu)")
row_nee="| nee (default) | \`skinbake bake --solver mc --preset refstack --target-error 0 --max-photons $NEE_N --batch-photons $NEE_B --estimator nee --out DIR\` | $photons | $secs | $cpu | $err | $eff_nee |"
bake bins --preset refstack --target-error 0 --max-photons "$BINS_N" --estimator bins
eff_bins=$(calc '%.4g' "1 / ($err * $err * $secs)") effc_bins=$(calc '%.6g' "1 / ($err * $err * $cpu)")
echo "| bins (MCML) | \`skinbake bake --solver mc --preset refstack --target-error 0 --max-photons $BINS_N --estimator bins --out DIR\` | $photons | $secs | $cpu | $err | $eff_bins | 1 | 1 |"
echo "$row_nee $(calc '%.1f' "$eff_nee / $eff_bins") | $(calc '%.1f' "$effc_nee / $effc_bins") |"
echo
echo "Roulette: \`skinbake bake\` has no roulette options, so this is \`skinbake simulate\` (plain"
echo "binning, no next-event estimation) on the \`refstack\` stack at 550 nm, normal incidence: the"
echo "defaults (roulette below weight 0.2, survival chance 0.3) against MCML's (1e-4, 0.1). Errors:"
echo "of Rd, and the RMS relative error of the 18 azimuth-averaged theta_o bands of 5 degrees."
echo
PAPER550="--layer d=0.001,n=1.5,mua=0,mus=0,g=0 --layer d=0.01,n=1.4,mua=50,mus=370,g=0.8 --layer d=0.25,n=1.4,mua=7,mus=370,g=0.8 --n-below 1.4"
echo "| roulette (weight, chance) | photons | seconds | events/photon | Rd | Rd error | band RMS error | efficiency Rd | gain Rd | efficiency bands | gain bands |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for rw in "1e-4 0.1" "0.05 0.3" "0.2 0.3"; do
	# shellcheck disable=SC2086
	set -- $rw
	# shellcheck disable=SC2086
	"$SKINBAKE" simulate $PAPER550 --photons "$SIM_N" --roulette-w "$1" --roulette-chance "$2" --json --r-bins 0 > "$W/sim.json"
	# shellcheck disable=SC2046,SC2086
	set -- $rw $(PY sim "$W/sim.json")
	er=$(calc '%.4g' "1 / ($6 * $6 * $4)") eb=$(calc '%.4g' "1 / ($7 * $7 * $4)")
	if [ "$1" = 1e-4 ]; then er0=$er eb0=$eb; fi
	echo "| $1, $2 | $3 | $4 | $8 | $5 | $6 | $7 | $er | $(calc '%.2f' "$er / $er0") | $eb | $(calc '%.2f' "$eb / $eb0") |"
done
echo
echo "Command: \`skinbake simulate $PAPER550 --photons $SIM_N --roulette-w W --roulette-chance P\`."

# --- Cost ----------------------------------------------------------------------
echo
echo "### Cost against table resolution, wavelengths and incidence angles"
echo
echo "Fixed photons per job ($PJ: \`--target-error 0 --max-photons N\`, where N is the total over"
echo "all jobs = wavelengths x angles x $PJ; \`--batch-photons $PJ_B\`), all cores. One wavelength"
echo "and one angle unless varied; the wavelengths and angles are close together so that every job"
echo "is about the same work and the cost should grow linearly."
echo
echo "| varied | command | jobs | bins per job | photons | seconds | CPU | seconds per job | seconds per job and 1000 bins |"
echo "|---|---|---|---|---|---|---|---|---|"
: > "$W/res.dat"
for r in $RES; do
	bins=$(( ${r%x*} * ${r#*x} ))
	bake "r$r" --preset refstack --wavelengths 550 --theta-in 30.0 --resolution "$r" --target-error 0 --max-photons "$PJ" --batch-photons "$PJ_B"
	echo "| resolution | \`skinbake bake --solver mc --preset refstack --wavelengths 550 --theta-in 30.0 --resolution $r --target-error 0 --max-photons $PJ --batch-photons $PJ_B --out DIR\` | $jobs | $bins | $photons | $secs | $cpu | $secs | $(calc '%.3f' "$secs / $bins * 1000") |"
	echo "$bins $secs" >> "$W/res.dat"
done
wls=550
for k in 1 2 4 8; do
	[ "$k" = 1 ] || wls=$(seq -s, 550 $((549 + k)))
	bake "w$k" --preset medium-oily --wavelengths "$wls" --theta-in 30.0 --target-error 0 --max-photons $((PJ * k)) --batch-photons "$PJ_B"
	echo "| wavelengths | \`skinbake bake --solver mc --preset medium-oily --wavelengths $wls --theta-in 30.0 --target-error 0 --max-photons $((PJ * k)) --batch-photons $PJ_B --out DIR\` | $jobs | 324 | $photons | $secs | $cpu | $(calc '%.3f' "$secs / $jobs") | - |"
done
ths=30.0
for k in 1 2 4 8; do
	[ "$k" = 1 ] || ths=$(seq -s, 30 $((29 + k)))
	bake "a$k" --preset refstack --wavelengths 550 --theta-in "$ths" --target-error 0 --max-photons $((PJ * k)) --batch-photons "$PJ_B"
	echo "| angles | \`skinbake bake --solver mc --preset refstack --wavelengths 550 --theta-in $ths --target-error 0 --max-photons $((PJ * k)) --batch-photons $PJ_B --out DIR\` | $jobs | 324 | $photons | $secs | $cpu | $(calc '%.3f' "$secs / $jobs") | - |"
done
fit=$(awk '{ n++; sx += $1; sy += $2; sxx += $1 * $1; sxy += $1 * $2 }
	END { b = (n * sxy - sx * sy) / (n * sxx - sx * sx); a = (sy - b * sx) / n;
	      printf "%.3f s + %.3g s per bin", a, b }' "$W/res.dat")
echo
echo "Least-squares line through the resolution rows: seconds = $fit."
echo
echo "One light against the full bake (\`refstack\`, 3 wavelengths, $PJ photons per job):"
echo
echo "| bake | command | jobs | photons | seconds | CPU | seconds per job |"
echo "|---|---|---|---|---|---|---|"
bake onefix --preset refstack --theta-in 30.0 --target-error 0 --max-photons $((PJ * 3)) --batch-photons "$PJ_B"
s_one=$secs c_one=$cpu
echo "| one light | \`skinbake bake --solver mc --preset refstack --theta-in 30.0 --target-error 0 --max-photons $((PJ * 3)) --batch-photons $PJ_B --out DIR\` | $jobs | $photons | $secs | $cpu | $(calc '%.3f' "$secs / $jobs") |"
if [ ! -d "$W/fullfix" ]; then
	bake fullfix --preset refstack --target-error 0 --max-photons "$FULL_N" --batch-photons "$FULL_B"
else
	# shellcheck disable=SC2046
	set -- $(PY info "$W/fullfix") $(cat "$W/c$FULL_N.cpu")
	photons=$1 secs=$2 jobs=$4 cpu=$5
fi
echo "| full (10 angles) | \`skinbake bake --solver mc --preset refstack --target-error 0 --max-photons $FULL_N --batch-photons $FULL_B --out DIR\` | $jobs | $photons | $secs | $cpu | $(calc '%.3f' "$secs / $jobs") |"
echo
echo "The full bake costs $(calc '%.1f' "$secs / $s_one") times the one-light bake ($(calc '%.1f' "$cpu / $c_one") in CPU time);"
echo "the ten angles (0 to 81 degrees) are not equally expensive, so 10 is not exact."
echo
echo "Load average at the end: $(load); this section took $(( $(date +%s) - t_start )) s."
