#!/bin/sh
# Every writer is all or nothing (issue 23 item 2): bake, family, texture,
# export pov, export blender and maps are killed (SIGKILL through strace's
# fault injection) at their k-th rename, renameat2, unlink, rmdir, mkdir,
# fsync, write and pwrite64, for k = 1, 2, ... until a run gets through.
# After every kill the output directory must hold one complete set: the
# old one or the new one, file for file (the new set always differs from
# the old, so that a mixture shows).  The run after a kill cleans up what
# the killed one left (checked at the end: nothing beside the directory).
#
# make check runs a bounded sweep: of the rare kinds every KILL_STEP_RARE-th
# call (default 3: k = 1, 4, 7, ...), of write and pwrite64 (hundreds per
# run) every KILL_STEP-th (default 80).  scripts/kill-sweep.sh runs the
# whole sweep (both steps 1: about 400 kills, 7 minutes), also with the
# exchange unavailable (KILL_EXCHANGE=no: the two-step fallback, where the
# directory may be absent for a moment but is never mixed).  KILL_WRITERS
# picks writers by name.  Costs about 2 minutes in make check.
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
T=$top_srcdir
: "${KILL_STEP:=80}" "${KILL_STEP_RARE:=3}" "${KILL_EXCHANGE:=yes}" "${KILL_WRITERS:=bake texture pov blender family maps}"
if ! command -v strace > /dev/null 2>&1; then
	skip "strace is missing (scripts/setup.sh installs it)"
	tap_done
	exit 0
fi
if ! strace -f -qq -o /dev/null true 2> /dev/null; then
	skip "strace cannot trace here (ptrace not permitted)"
	tap_done
	exit 0
fi
cd "$tmpd" || exit 1
BK="--preset paper --solver ad --theta-nodes 3 --radial-error 0.2 --r-bins 20 --quiet"
FAM="--preset paper --solver ad --theta-nodes 2 --resolution 3x3 --radial-error 0.3 --r-bins 10 --quiet"
"$B" bake $BK --resolution 9x6 --out bk && "$B" texture --size 16 --out tx --quiet &&
	"$B" bake $FAM --vary dermis.blood=0.01:0.03:2 --out fam || fail "the inputs"

# The command of WRITER for generation G (a or b), without --out.
cmd() {
	case $1 in
	bake) echo "bake $BK --resolution $([ "$2" = a ] && echo 9x6 || echo 9x7)" ;;
	texture) echo "texture --size 16 --quiet --seed $([ "$2" = a ] && echo 1 || echo 2)" ;;
	pov) echo "export pov --bake bk --scene $T/scenes/sphere.scene --nodes $([ "$2" = a ] && echo 9 || echo 17)" ;;
	blender) echo "export blender --bake bk --textures tx --lut-cos 8 --lut-phi $([ "$2" = a ] && echo 3 || echo 4)" ;;
	family) echo "bake $FAM --vary dermis.blood=0.01:$([ "$2" = a ] && echo 0.03 || echo 0.04):2" ;;
	maps) echo "maps new --family fam --size 8x8 --quiet --set dermis.blood=$([ "$2" = a ] && echo 0.02 || echo 0.025)" ;;
	esac
}

# A fingerprint of DIR: every file with its checksum, the manifests' wall
# times left out (they differ between runs of one command).
print() {
	[ -e "$1" ] || { echo absent; return; }
	(cd "$1" && find . -type f | LC_ALL=C sort | while read -r f; do
		printf '%s %s\n' "$f" "$(grep -av '"seconds":' "$f" | md5sum)"
	done)
}

for w in $KILL_WRITERS; do
	t=$tmpd/$w/out
	mkdir -p "$tmpd/$w"
	# The two sets, written where the sweep writes (paths show in manifests).
	# shellcheck disable=SC2046
	"$B" $(cmd $w a) --out "$t" > /dev/null 2>&1 && print "$t" > "$w.a" &&
		"$B" $(cmd $w b) --out "$t" > /dev/null 2>&1 && print "$t" > "$w.b" &&
		"$B" $(cmd $w a) --out "$t" > /dev/null 2>&1 || { fail "$w: the uninterrupted runs"; continue; }
	cmp -s "$w.a" "$w.b" && { fail "$w: generations a and b do not differ"; continue; }
	gen=a kills=0 bad=0 absent=0
	inject=
	[ "$KILL_EXCHANGE" = no ] && inject="-e inject=renameat2:error=EINVAL"
	for call in rename renameat2 unlink rmdir mkdir fsync write pwrite64; do
		step=$KILL_STEP_RARE
		case $call in write | pwrite64) step=$KILL_STEP ;; esac
		k=1
		while [ $k -lt 5000 ]; do
			new=$([ $gen = a ] && echo b || echo a)
			# LeakSanitizer (--enable-asan) stops the world with ptrace,
			# which strace holds: off for the traced run.
			# shellcheck disable=SC2046,SC2086
			ASAN_OPTIONS=detect_leaks=0 strace -f -qq -o /dev/null $inject \
				-e inject=$call:signal=SIGKILL:when=$k "$B" $(cmd $w $new) --out "$t" > /dev/null 2> err
			rc=$?
			print "$t" > now
			if cmp -s now "$w.$new"; then
				gen=$new
			elif [ "$(cat now)" = absent ] && [ "$KILL_EXCHANGE" = no ] && [ $rc -eq 137 ]; then
				absent=$((absent + 1))
			elif ! cmp -s now "$w.$gen"; then
				bad=$((bad + 1))
				echo "# $w, $call $k (exit $rc): neither the old nor the new set: $(diff "$w.$gen" now | head -4 | tr '\n' ' ')"
			fi
			[ $rc -eq 0 ] && break
			if [ $rc -ne 137 ]; then
				bad=$((bad + 1))
				echo "# $w, $call $k: the writer failed (exit $rc): $(head -3 err)"
				break
			fi
			kills=$((kills + 1))
			k=$((k + step))
		done
	done
	# shellcheck disable=SC2046
	"$B" $(cmd $w a) --out "$t" > /dev/null 2> err || { bad=$((bad + 1)); echo "# $w, last run: $(head -3 err)"; }
	print "$t" | cmp -s - "$w.a" || { bad=$((bad + 1)); echo "# $w: the last run did not write set a"; }
	left=$(ls -A "$tmpd/$w" | grep -v '^out$' | tr '\n' ' ')
	[ -z "$left" ] || { bad=$((bad + 1)); echo "# $w: left beside the output: $left"; }
	echo "# $w: $kills kills, $absent of them left no directory (no exchange)"
	check "$w: a kill at each of $kills calls left the old or the new complete set; the next run cleaned up" \
		[ $bad -eq 0 -a $kills -gt 5 ]
done
tap_done
