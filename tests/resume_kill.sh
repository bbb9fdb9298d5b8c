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
. "$top_srcdir/tests/lib/resume.sh"

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
check "mc: resumed tables and manifest equal the uninterrupted ones" resume_same ref mc
check "mc: the checkpoint is gone after the bake" [ ! -e mc.checkpoint ]

# Rounds sized from a pilot (mc.h): killed after the pilot's checkpoint.
MR="--preset paper --solver mc --theta-nodes 3 --resolution 9x6 --target-error 0.03 --r-bins 20 --quiet
	--checkpoint-seconds 0"
check "mc rounds: uninterrupted bake" "$B" bake $MR --out refr
check "mc rounds: killed after the pilot's checkpoint" killat rounds 1 "$B" bake $MR --out rounds
check "mc rounds: --resume" "$B" bake $MR --out rounds --resume
check "mc rounds: resumed tables and manifest equal the uninterrupted ones" resume_same refr rounds

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
check "ad: resumed tables and manifest equal the uninterrupted ones" resume_same refad ad

check "--resume without a checkpoint bakes from the start" "$B" bake $AD --out fresh --resume
check "... the same tables" resume_same refad fresh
# The comparison can fail: one byte of a table changed is caught.
cp -r ref probe && printf x | dd of=probe/brdf.exr bs=1 seek=100 conv=notrunc 2>/dev/null
if resume_same ref probe >/dev/null; then fail "probe: a table changed in one byte passes"; else ok "probe: a table changed in one byte is caught"; fi
printf 'skinbake checkpoint 1\ngarbage' > bad.checkpoint
"$B" bake $AD --out bad --resume 2> err.txt
check "a damaged checkpoint: exit 2" [ $? -eq 2 ]
check "... naming it" grep -q "bad.checkpoint is not a complete skinbake checkpoint" err.txt
check "... and no output" [ ! -e bad ]
tap_done
