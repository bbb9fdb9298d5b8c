#!/bin/sh
# Checkpoints (src/bake/checkpoint.c): a bake SIGKILLed after its first
# checkpoint and run again with --resume writes every table byte for byte as
# the uninterrupted bake, and a manifest equal but for its command line and
# wall times.  Monte Carlo (9 jobs, 111 batches of 100 photons each: 4
# steps) is killed once, and so is one sized by a pilot (--target-error); adding-doubling (13 wavelengths, then the Rd(r)
# runs of Monte Carlo) is killed twice, the second time after a later solver
# run was saved, so that finished runs are restored too.  Also: a stale
# checkpoint without --resume is exit 2 and names --resume; --resume of a
# changed command (another seed) is exit 2; --resume without a checkpoint
# bakes from the start; a damaged checkpoint is exit 2.  Costs about 10 s.
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
cd "$tmpd" || exit 1

# same REF DIR: every file of REF equal in DIR (manifest: but command and seconds)
same() {
	for f in "$1"/*; do
		g="$2/$(basename "$f")"
		case $f in
		*.json) grep -v -e '"command":' -e '"seconds":' "$f" > a.json
			grep -v -e '"command":' -e '"seconds":' "$g" > b.json
			cmp -s a.json b.json || { echo "# $g differs"; return 1; } ;;
		*) cmp -s "$f" "$g" || { echo "# $g differs"; return 1; } ;;
		esac
	done
	[ "$(ls "$1" | wc -l)" -eq "$(ls "$2" | wc -l)" ]
}

# runs DIR: the solver runs saved in DIR.checkpoint (its uint32 after the
# 23-byte header line and the 8-byte identity), 0 without one
runs() {
	n=$(od -An -tu4 -j31 -N4 "$1.checkpoint" 2>/dev/null | tr -d ' ')
	echo "${n:-0}"
}

# killat DIR N CMD...: start CMD, SIGKILL it once DIR.checkpoint holds N
# solver runs; 0 when it was killed that way, 1 when it ended first
killat() {
	kdir=$1 kn=$2
	shift 2
	"$@" & pid=$!
	while kill -0 $pid 2>/dev/null; do
		[ "$(runs "$kdir")" -ge "$kn" ] && break
		sleep 0.02
	done
	kill -9 $pid 2>/dev/null
	wait $pid
	[ $? -eq 137 ]
}

MC="--preset paper --solver mc --theta-nodes 3 --resolution 9x6 --target-error 0 --max-photons 100000
	--batch-photons 100 --r-bins 20 --quiet --checkpoint-seconds 0"
check "mc: uninterrupted bake" "$B" bake $MC --out ref
check "mc: killed after its first checkpoint" killat mc 1 "$B" bake $MC --out mc
check "mc: the killed bake left a checkpoint and no output" test -s mc.checkpoint -a ! -e mc
"$B" bake $MC --out mc 2> err.txt
check "mc: a stale checkpoint without --resume: exit 2" [ $? -eq 2 ]
check "mc: ... and the message says to pass --resume or remove it" grep -q "mc.checkpoint.*--resume.*remove" err.txt
"$B" bake $MC --seed 2 --out mc --resume 2> err.txt
check "mc: --resume with another seed: exit 2 (another bake)" [ $? -eq 2 ]
check "mc: ... naming the checkpoint" grep -q "mc.checkpoint was written by a different bake" err.txt
check "mc: --resume" "$B" bake $MC --out mc --resume
check "mc: resumed tables and manifest equal the uninterrupted ones" same ref mc
check "mc: the checkpoint is gone after the bake" [ ! -e mc.checkpoint ]

# Rounds sized from a pilot (mc.h): killed after the pilot's checkpoint.
MR="--preset paper --solver mc --theta-nodes 3 --resolution 9x6 --target-error 0.03 --r-bins 20 --quiet
	--checkpoint-seconds 0"
check "mc rounds: uninterrupted bake" "$B" bake $MR --out refr
check "mc rounds: killed after the pilot's checkpoint" killat rounds 1 "$B" bake $MR --out rounds
check "mc rounds: --resume" "$B" bake $MR --out rounds --resume
check "mc rounds: resumed tables and manifest equal the uninterrupted ones" same refr rounds

AD="--preset fair-oily --spectral 400:700:25 --theta-nodes 3 --resolution 9x6 --radial-photons 20000 --r-bins 20
	--quiet --threads 1 --checkpoint-seconds 0"
check "ad: uninterrupted bake" "$B" bake $AD --out refad
check "ad: killed after its first checkpoint" killat ad 1 "$B" bake $AD --out ad
if killat ad 2 "$B" bake $AD --out ad --resume; then
	ok "ad: resumed, killed again after a later solver run was saved"
else
	skip "ad: the resumed bake ended before the second kill (a slower machine kills it)"
fi
check "ad: --resume" "$B" bake $AD --out ad --resume
check "ad: resumed tables and manifest equal the uninterrupted ones" same refad ad

check "--resume without a checkpoint bakes from the start" "$B" bake $AD --out fresh --resume
check "... the same tables" same refad fresh
printf 'skinbake checkpoint 1\ngarbage' > bad.checkpoint
"$B" bake $AD --out bad --resume 2> err.txt
check "a damaged checkpoint: exit 2" [ $? -eq 2 ]
check "... naming it" grep -q "bad.checkpoint is not a complete skinbake checkpoint" err.txt
check "... and no output" [ ! -e bad ]
tap_done
