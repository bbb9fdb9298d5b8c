#!/bin/sh
# An output directory replaced as a whole (src/base/outdir.c) survives a
# SIGKILL at every rename, unlink, rmdir and fsync of a run (strace's fault
# injection): afterwards a reader finds the complete old set or the complete
# new one (with the exchange), or, where the file system cannot exchange two
# directories (renameat2 failing with EINVAL, injected), also no directory;
# never a mixture.  The next run removes what the killed one left and
# completes.  Costs about 2 s.
. "$top_srcdir/tests/tap.sh"
W="$top_builddir/tests/outdir_writer"
N=3
if ! command -v strace >/dev/null 2>&1; then
	skip "strace is missing (scripts/setup.sh installs it)"
	tap_done
	exit 0
fi
if ! strace -f -qq -o /dev/null true 2>/dev/null; then
	skip "strace cannot trace here (ptrace not permitted)"
	tap_done
	exit 0
fi

# The generation of a complete set in $1, "absent", or "MIXED: ..." .
state() {
	[ -e "$1" ] || { echo absent; return; }
	want="manifest.json sub"
	i=0
	while [ $i -lt $N ]; do want="$want f$i.txt"; i=$((i + 1)); done
	have=$(cd "$1" && ls -A | sort | tr '\n' ' ')
	want=$(echo $want | tr ' ' '\n' | sort | tr '\n' ' ')
	[ "$have" = "$want" ] || { echo "MIXED: files $have"; return; }
	[ "$(ls -A "$1/sub")" = g.txt ] || { echo "MIXED: sub holds $(ls -A "$1/sub")"; return; }
	gens=$(cat "$1"/*.txt "$1/manifest.json" "$1/sub/g.txt" | sort -u | tr '\n' ' ')
	case $gens in
	*" "?*) echo "MIXED: generations $gens" ;;
	*) echo "$gens" | tr -d ' ' ;;
	esac
}

# leftovers DIR: staging or retired directories beside it
leftovers() { ls -A "$(dirname "$1")" | grep -c "^\.$(basename "$1")\." ; }

for mode in exchange no-exchange; do
	t="$tmpd/$mode/out"
	mkdir -p "$tmpd/$mode"
	inject= calls="rename renameat2 unlink rmdir fsync"
	if [ $mode = no-exchange ]; then
		inject="-e inject=renameat2:error=EINVAL"
		calls="rename unlink rmdir fsync"
	fi
	"$W" "$t" 0 $N
	gen=0 kills=0 bad=0 stale=0
	# strace counts each system call apart: kill at its 1st, 2nd, ... call
	# until a run gets through.
	for call in $calls; do
		k=1
		while [ $k -lt 100 ]; do
			new=$((gen + 1))
			# LeakSanitizer (--enable-asan) stops the world with ptrace, which
			# strace holds: off for the traced run.
			# shellcheck disable=SC2086
			ASAN_OPTIONS=detect_leaks=0 strace -f -qq -o /dev/null $inject \
				-e inject=$call:signal=SIGKILL:when=$k "$W" "$t" $new $N 2>"$tmpd/err"
			rc=$?
			s=$(state "$t")
			if [ $rc -eq 0 ]; then
				[ "$s" = $new ] || { bad=$((bad + 1)); echo "# $mode: a run that was not killed left '$s'"; }
				gen=$new
				break
			fi
			if [ $rc -ne 137 ]; then
				bad=$((bad + 1))
				echo "# $mode, $call $k: the writer failed (exit $rc): $(head -3 "$tmpd/err")"
				break
			fi
			kills=$((kills + 1))
			case "$s" in
			"$gen" | "$new") ;;
			absent) [ $mode = no-exchange ] || { bad=$((bad + 1)); echo "# $mode, $call $k: target absent"; } ;;
			*) bad=$((bad + 1)); echo "# $mode, $call $k: $s" ;;
			esac
			[ "$(leftovers "$t")" -gt 0 ] && stale=$((stale + 1))
			# The next run cleans up after the killed one and completes.
			gen=$((new + 1))
			"$W" "$t" $gen $N 2>"$tmpd/err" || { bad=$((bad + 1)); echo "# $mode, $call $k, next run: $(cat "$tmpd/err")"; }
			s=$(state "$t")
			[ "$s" = $gen ] || { bad=$((bad + 1)); echo "# $mode, $call $k, next run: $s"; }
			[ "$(leftovers "$t")" -eq 0 ] || { bad=$((bad + 1)); echo "# $mode, $call $k, next run left $(ls -A "$tmpd/$mode")"; }
			k=$((k + 1))
		done
	done
	echo "# $mode: $kills kills, $stale of them left staging or the old set beside the target"
	check "$mode: a kill at each of $kills calls ($calls) left a complete set; the next run cleaned up" \
		[ $bad -eq 0 -a $kills -gt 15 -a $kills -lt 60 ]
done
tap_done
