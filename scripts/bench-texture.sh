#!/bin/sh
# Time `skinbake texture` for a 4096 x 4096 combined map of the hand (three
# furrow levels, the most work of the sites) and print a markdown section with one table row.
# Uses $SKINBAKE (the built binary).  Not a test: timings vary with the load.
set -e
: "${SKINBAKE:=./skinbake}"
site=${1:-hand}
size=${2:-4096}
out=$(mktemp -d "${TMPDIR:-/tmp}/skinbake-bench.XXXXXX")
trap 'rm -rf "$out"' EXIT
load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo ?)
t0=$(date +%s.%N)
"$SKINBAKE" texture --site "$site" --size "$size" --out "$out" 2>"$out.log"
t1=$(date +%s.%N)
# The command reports its own split: place / render (incl. normals) / write.
split=$(sed -n 's/.*place \([0-9.]*\) s, render \([0-9.]*\) s, write \([0-9.]*\) s.*/place \1 s, render+normals \2 s, write \3 s/p' "$out.log")
rm -f "$out.log"
threads=${OMP_NUM_THREADS:-$(nproc 2>/dev/null || echo ?)}
# Under `make bench` this is one section of BENCHMARKS.md.
echo "## Micro-geometry"
echo
echo "Command: \`skinbake texture --site $site --size $size --out DIR\` (scripts/bench-texture.sh),"
echo "$(date -u +%Y-%m-%d), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load average $load"
echo "at the start (the machine's other jobs share its cores; a load above the thread count stretches the wall time)."
echo
echo "| map | threads | wall time | split |"
echo "|---|---|---|---|"
printf '| texture %s %dx%d (all maps) | %s threads | %.2f s total | %s |\n' "$site" "$size" "$size" \
    "$threads" "$(awk "BEGIN { print $t1 - $t0 }")" "$split"
