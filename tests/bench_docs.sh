#!/bin/sh
# BENCHMARKS.md is what `make bench` writes and nothing else: the sections docs/bench/NAME.md of
# the scripts in BENCHMARK_SCRIPTS_LIST (the .am files), joined by scripts/bench-assemble.sh
# (`make bench-docs` joins them again without running anything). A section written into
# BENCHMARKS.md by hand, which the next `make bench` would delete, fails here; so does a script
# without its section or a section without its script.
. "$top_srcdir/tests/tap.sh"
cd "$top_srcdir" || exit 1
list=$(cat Makefile.am src/*/*.am src/*/*/*.am | sed -n 's/^BENCHMARK_SCRIPTS_LIST *+*= *//p' | tr ' ' '\n' | grep .)
check "make bench runs scripts (BENCHMARK_SCRIPTS_LIST: $(echo $list | wc -w))" test -n "$list"
for s in $list; do
	n=$(basename "$s" .sh)
	check "$s: its section docs/bench/$n.md is there" test -s "docs/bench/$n.md"
done
for f in docs/bench/*.md; do
	n=$(basename "$f" .md)
	check "$f: written by a listed script (scripts/$n.sh)" sh -c "echo '$list' | grep -qx 'scripts/$n.sh'"
done
top_srcdir="$tmpd" BENCH_OUT="$PWD/docs/bench" sh scripts/bench-assemble.sh
if cmp -s "$tmpd/BENCHMARKS.md" BENCHMARKS.md; then
	ok "BENCHMARKS.md is the sections joined, nothing written by hand"
else
	fail "BENCHMARKS.md differs from the sections joined (docs/bench/*.md; \`make bench-docs\` joins them): $(diff "$tmpd/BENCHMARKS.md" BENCHMARKS.md | head -3 | tr '\n' ' ')"
fi
# Probe: a line added by hand is caught.
cp "$tmpd/BENCHMARKS.md" "$tmpd/hand.md"
echo "A hand-written figure: 12 s." >>"$tmpd/hand.md"
check "probe: a hand-written line in BENCHMARKS.md is caught" sh -c "! cmp -s '$tmpd/BENCHMARKS.md' '$tmpd/hand.md'"
tap_done
