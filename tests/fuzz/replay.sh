#!/bin/sh
# The committed fuzz corpus (tests/fuzz/corpus/NAME: seeds, inputs the
# fuzzers found interesting, and every input that once crashed a reader)
# through each fuzz target, built as a plain program: runs in every build,
# under the sanitizers when configured with --enable-asan.
. "$top_srcdir/tests/tap.sh"
for n in preset scene texture manifest exr png; do
	out=$("$top_builddir/tests/fuzz/replay_$n" "$top_srcdir/tests/fuzz/corpus/$n" 2>"$tmpd/$n.err")
	rc=$?
	if [ $rc -eq 0 ]; then
		ok "$n: corpus replayed (${out##*: })"
	else
		fail "$n: corpus replay failed (exit $rc)"
		sed 's/^/# /' "$tmpd/$n.err" | head -40
	fi
done
tap_done
