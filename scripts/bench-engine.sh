#!/bin/sh
# Engine benchmarks: throughput (one and all threads), time to a given
# error, error against photons with a plot.  Prints a markdown section;
# plots go to $BENCH_OUT (default docs/bench).
set -eu
SKINBAKE=${SKINBAKE:-./skinbake}
top_srcdir=${top_srcdir:-.}
OUT=${BENCH_OUT:-$top_srcdir/docs/bench}
mkdir -p "$OUT"
MCML="--layer d=0.02,n=1,mua=10,mus=90,g=0.75"
SKIN="--layer d=0.001,n=1.5,mua=0,mus=0,g=0 --layer d=0.01,n=1.4,mua=50,mus=370,g=0.8 --layer d=0.25,n=1.4,mua=7,mus=370,g=0.8 --n-below 1.4"
J() { python3 -c "import json,sys; d=json.load(sys.stdin); print($1)"; }
run() { "$SKINBAKE" simulate "$@" --json --r-bins 0; }
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')
echo "## Transport engine"
echo
echo "Machine: $cpu, $(nproc) cores; $(date -u +%Y-%m-%d). Command: \`make bench\` (scripts/bench-engine.sh)."
echo
echo "### Throughput"
echo
echo "| stack | threads | photons | seconds | photons/s | scattering events/s | events/photon |"
echo "|---|---|---|---|---|---|---|"
for stack in MCML SKIN; do
	eval "L=\$$stack"
	for t in 1 0; do
		# shellcheck disable=SC2086
		run $L --photons 1e6 --threads $t > "$OUT/tp.json"
		J "'| %s | %s | %d | %.2f | %.3g | %.3g | %.1f |' % ('$stack'.replace('MCML','MCML benchmark slab').replace('SKIN','skin stack (550 nm)'), '$t'.replace('0','all ($(nproc))'), d['photons'], d['seconds'], d['photons_per_second'], d['events_per_second'], d['scattering_events']/d['photons'])" < "$OUT/tp.json"
	done
done
# The refstack preset's three wavelengths (the reference stack; `paper` before issue 16),
# with the layers `skinbake preset show refstack` resolves.
for wl in 470 550 656; do
	L=$("$SKINBAKE" preset show refstack | awk -v w=$wl '$1 == w { printf " --layer d=%s,n=%s,mua=%s,mus=%s,g=%s", $3, $4, $5, $6, $7 }')
	for t in 1 0; do
		# shellcheck disable=SC2086
		run $L --n-below 1.4 --photons 1e6 --threads $t > "$OUT/tp.json"
		J "'| refstack preset, %s nm | %s | %d | %.2f | %.3g | %.3g | %.1f |' % ('$wl', '$t'.replace('0','all ($(nproc))'), d['photons'], d['seconds'], d['photons_per_second'], d['events_per_second'], d['scattering_events']/d['photons'])" < "$OUT/tp.json"
	done
done
echo
echo "Scaling (all threads over one) is the ratio of the photons/s columns. The refstack rows use the"
echo "layers of \`skinbake preset show refstack\` with \`skinbake simulate ... --n-below 1.4 --photons 1e6\`."
echo
echo "### Skin stack: Rd to a standard error of 7.4e-5 (0.1%), one thread"
echo
# shellcheck disable=SC2086
run $SKIN --photons 2e5 --threads 1 > "$OUT/pilot.json"
n=$(J "int(d['photons']*(d['Rd_err']/7.4e-5)**2*1.05)" < "$OUT/pilot.json")
# shellcheck disable=SC2086
run $SKIN --photons "$n" --threads 1 > "$OUT/target.json"
J "'| photons | seconds | Rd | Rd std. error | AD reference | difference |\n|---|---|---|---|---|---|\n| %d | %.2f | %.6f | %.2e | 0.073813 | %+.2e (%.1f sigma) |' % (d['photons'], d['seconds'], d['Rd'], d['Rd_err'], d['Rd']-0.073813, (d['Rd']-0.073813)/d['Rd_err'])" < "$OUT/target.json"
echo
echo "Command: \`skinbake simulate $SKIN --photons $n --threads 1\`. Defaults: roulette below"
echo "weight 0.2 with chance 0.3. For scale, MCML 1.2.2 needs about 100 s for this error on this"
echo "machine (about 37,000 photons/s) and reads 1.4% high (refs/README.md)."
echo
echo "### Skin stack: azimuth-averaged BRDF at normal incidence, 18 bands of 5 degrees, to 1% RMS relative error, all threads"
echo
# shellcheck disable=SC2086
run $SKIN --photons 2e5 --threads 0 > "$OUT/bp.json"
rms() { J "(lambda fr,fe: (sum(((e/f) if f>0 else 1)**2 for f,e in zip(fr,fe))/len(fr))**0.5)(d['brdf_az']['fr'], d['brdf_az']['fr_err'])"; }
e0=$(rms < "$OUT/bp.json")
n=$(python3 -c "print(int(2e5*($e0/0.01)**2*1.05))")
# shellcheck disable=SC2086
run $SKIN --photons "$n" --threads 0 > "$OUT/bt.json"
e1=$(rms < "$OUT/bt.json")
J "'| estimator | photons | seconds | RMS relative error |\n|---|---|---|---|\n| plain band tallies (simulate) | %d | %.2f | %.4f |' % (d['photons'], d['seconds'], float('$e1'))" < "$OUT/bt.json"
# The same quantity as a one-column bake of the same stack (the `refstack` preset at 550 nm is
# this skin stack): next-event estimation, stopping at 1% by itself.
"$SKINBAKE" bake --preset refstack --wavelengths 550 --theta-in 0 --resolution 18x1 --target-error 0.01 \
	--batch-photons 500 --out "$OUT/az-bake" --quiet
python3 -c "import json; r=json.load(open('$OUT/az-bake/manifest.json'))['result']; print('| next-event estimation (bake) | %d | %.2f | %.4f |' % (r['photons'], r['seconds'], r['rms_rel_err']))"
rm -rf "$OUT/az-bake"
echo
echo "Commands: \`skinbake simulate SKIN --photons N\` (bands of 5 degrees, azimuth-averaged), and"
echo "\`skinbake bake --preset refstack --wavelengths 550 --theta-in 0 --resolution 18x1 --target-error 0.01 --batch-photons 500\`"
echo "(18 bands x 1 azimuth bin = the azimuth average). MCML needs about half a minute of one core."
echo
echo "### Error against photons (skin stack Rd, one thread)"
echo
echo "| photons | seconds | Rd | reported std. error | \|Rd - AD\| |"
echo "|---|---|---|---|---|"
: > "$OUT/conv.dat"
for n in 1e4 3e4 1e5 3e5 1e6 3e6; do
	# shellcheck disable=SC2086
	run $SKIN --photons $n --threads 1 > "$OUT/c.json"
	J "'| %d | %.3f | %.6f | %.2e | %.2e |' % (d['photons'], d['seconds'], d['Rd'], d['Rd_err'], abs(d['Rd']-0.073813))" < "$OUT/c.json"
	J "'%d %g %g %g' % (d['photons'], d['seconds'], d['Rd_err'], abs(d['Rd']-0.073813))" < "$OUT/c.json" >> "$OUT/conv.dat"
done
if command -v gnuplot >/dev/null 2>&1; then
	gnuplot <<GP
set terminal pngcairo size 640,440
set output "$OUT/engine_error_vs_time.png"
set termoption noenhanced
set logscale xy
set xlabel "seconds (one thread)"
set ylabel "error of Rd"
set key bottom left
set title "skin stack Rd: error against time"
first = system("head -1 $OUT/conv.dat | cut -d' ' -f2") + 0
firste = system("head -1 $OUT/conv.dat | cut -d' ' -f3") + 0
plot "$OUT/conv.dat" using 2:3 with linespoints title "reported standard error", \
     "$OUT/conv.dat" using 2:4 with points pt 7 title "|Rd - adding-doubling|", \
     firste*sqrt(first/x) with lines dt 2 title "1/sqrt(N) guide"
GP
	echo
	echo "![error against time](docs/bench/engine_error_vs_time.png)"
fi
rm -f "$OUT"/*.json
