#!/bin/sh
# Write BENCHMARKS.md from the sections that `make bench` collected.
set -eu
top_srcdir=${top_srcdir:-.}
OUT=${BENCH_OUT:-$top_srcdir/docs/bench}
{
	echo "# skinbake benchmarks"
	echo
	echo "Every figure below was produced by \`make bench\`, which runs the scripts in"
	echo "\`BENCHMARK_SCRIPTS_LIST\` (scripts/bench-*.sh) and rewrites this file. Timings are wall"
	echo "clock on the machine named in each section; errors are statistical standard errors unless"
	echo "a reference is named."
	for f in "$OUT"/*.md; do
		[ -f "$f" ] || continue
		echo
		cat "$f"
	done
} > "$top_srcdir/BENCHMARKS.md.tmp"
mv "$top_srcdir/BENCHMARKS.md.tmp" "$top_srcdir/BENCHMARKS.md"
