#!/bin/sh
# Timings on a quiet machine (BENCHMARKS.md): the `paper` bake by
# adding-doubling (best of 3) and by Monte Carlo at 0.01 (one run), and
# every 16-wavelength physiological preset by adding-doubling (best of 3),
# wall seconds around each command.  Run it when nothing else runs: the
# section states the load average before and after.  Prints one markdown
# section; `make bench` runs it (BENCHMARK_SCRIPTS_LIST).
set -eu
SKINBAKE=${SKINBAKE:-./skinbake}
W=$(mktemp -d "${TMPDIR:-/tmp}/skinbake-bench-timing.XXXXXX")
trap 'rm -rf "$W"' EXIT INT TERM
load() { cut -d' ' -f1 /proc/loadavg; }
# wall ARGS...: wall seconds of one `skinbake bake ARGS --out $W/b --quiet`.
wall() {
	t0=$(date +%s.%N)
	"$SKINBAKE" bake "$@" --out "$W/b" --quiet >/dev/null
	t1=$(date +%s.%N)
	awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }'
}
# best ARGS...: the best of 3 wall times.
best() {
	b=
	for i in 1 2 3; do
		t=$(wall "$@")
		b=$(awk -v a="${b:-1e9}" -v t="$t" 'BEGIN { printf "%.2f", t < a ? t : a }')
	done
	echo "$b"
}
# rms: the last bake's estimated RMS relative error (manifest solver.rms_rel_err).
rms() { python3 -c 'import json, sys; print("%.2g" % json.load(open(sys.argv[1]))["solver"]["rms_rel_err"])' "$W/b/manifest.json"; }
l0=$(load)
start=$(date -u '+%Y-%m-%d %H:%M UTC')
ad=$(best --preset paper --solver ad)
ad_err=$(rms)
/usr/bin/time -f '%e %U %S' -o "$W/mc" "$SKINBAKE" bake --preset paper --solver mc --target-error 0.01 \
	--out "$W/b" --quiet >/dev/null
mc_wall=$(awk '{ printf "%.1f", $1 }' "$W/mc")
mc_cpu=$(awk '{ printf "%.0f", $2 + $3 }' "$W/mc")
mc_err=$(rms)
row() {
	names=
	times=
	for p in "$@"; do
		names="$names${names:+, }$p"
		times="$times${times:+, }$(best --preset "$p")"
	done
	echo "| $names | $times |"
}
echo "## Timings on a quiet machine"
echo
echo "Commands run alone ($start, 1-minute load $l0 before and $(load) after, $(nproc) cores), wall seconds"
echo "measured with \`date\` around each command, best of 3 (Monte Carlo: one run); scripts/bench-timing.sh:"
echo
echo "| bake | wall [s] |"
echo "|---|---|"
echo "| \`skinbake bake --preset paper --solver ad --out DIR\` (estimated RMS error $ad_err) | $ad |"
echo "| \`skinbake bake --preset paper --solver mc --target-error 0.01 --out DIR\` (one run; standard error $mc_err; $mc_cpu s CPU) | $mc_wall |"
row very-fair-oily very-fair-dry fair-oily fair-dry
row medium-oily medium-dry olive-oily olive-dry
row brown-oily brown-dry dark-oily dark-dry
echo
echo "\`paper\` by adding-doubling is $(awk -v a="$ad" -v m="$mc_wall" 'BEGIN { printf "%.0f", m / a }')x faster in wall time than Monte Carlo at 0.01 (goal: 30x)."
