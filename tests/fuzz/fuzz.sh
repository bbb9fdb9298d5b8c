#!/bin/sh
# libFuzzer on each reader of outside files (./configure --enable-fuzzing):
# FUZZ_SECONDS per target (default 10: about 60 s in all in make check;
# make fuzz sets 600).  Starts from the committed corpus; new inputs go to a
# scratch corpus, or to $FUZZ_KEEP/corpus/NAME when FUZZ_KEEP is set (make
# fuzz), crashing inputs to $FUZZ_KEEP/crashes/NAME or the build directory's
# fuzz-crashes/NAME.  Prints executions and time per target.
. "$top_srcdir/tests/tap.sh"
secs=${FUZZ_SECONDS:-10}
keep=${FUZZ_KEEP:-}
total_runs=0
total_secs=0
for n in ${FUZZ_TARGETS:-preset scene texture manifest exr png}; do
	if [ -n "$keep" ]; then
		corpus="$keep/corpus/$n"
		crashes="$keep/crashes/$n"
	else
		corpus="$tmpd/corpus-$n"
		crashes="$top_builddir/fuzz-crashes/$n"
	fi
	mkdir -p "$corpus" "$crashes" "$tmpd/tmp"
	dict="$top_srcdir/tests/fuzz/dict/$n.dict"
	[ -f "$dict" ] && dopt="-dict=$dict" || dopt=
	t0=$(date +%s)
	TMPDIR="$tmpd/tmp" "$top_builddir/tests/fuzz/fuzz_$n" -max_total_time="$secs" -timeout=10 \
		-rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$crashes/" $dopt \
		"$corpus" "$top_srcdir/tests/fuzz/corpus/$n" >"$tmpd/$n.log" 2>&1
	rc=$?
	t1=$(date +%s)
	runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$tmpd/$n.log" | tail -1)
	[ -n "$runs" ] || runs=0
	total_runs=$((total_runs + runs))
	total_secs=$((total_secs + t1 - t0))
	if [ $rc -eq 0 ]; then
		ok "$n: $runs executions in $((t1 - t0)) s, no crash, leak or undefined behaviour"
	else
		fail "$n: libFuzzer stopped (exit $rc) after $runs executions; inputs in $crashes"
		grep -v '^#' "$tmpd/$n.log" | grep -A30 -m1 'ERROR\|runtime error\|fuzz:' | sed 's/^/# /'
	fi
done
echo "# fuzzing: $total_runs executions in $total_secs s"
tap_done
