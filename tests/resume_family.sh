#!/bin/sh
# Family checkpoints (src/family/family_run.c): a family bake (3 members,
# adding-doubling) SIGKILLed once FAM.checkpoint holds its first member and
# run again with --resume writes a family directory equal to the
# uninterrupted one: every EXR and PNG byte for byte, family.json and the
# members' manifests but for the command line and wall times.  Also: a
# stale checkpoint without --resume is exit 2 and names --resume; --resume
# of a changed command (another --vary range) is exit 2; a torn append is
# ignored, a changed saved byte refused; under MPI --resume
# is refused (exit 2).  Costs about 8 s CPU (each member about 1 s).
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
cd "$tmpd" || exit 1
. "$top_srcdir/tests/lib/resume.sh"

# differ A B: files A and B are not equal
differ() { ! cmp -s "$1" "$2"; }

F="--preset fair-oily --solver ad --theta-nodes 2 --resolution 6x4 --radial-photons 10000 --r-bins 10 --threads 1
	--checkpoint-seconds 0 --quiet"
V="--vary dermis.blood=0.01:0.05:3:lin"
check "family: uninterrupted bake" "$B" bake $F $V --out ref
check "family: killed after its first member was saved" killat fam 1 "$B" bake $F $V --out fam
check "family: the killed bake left a checkpoint of 1 member and no output" \
	[ "$(ckpt_count fam)" -eq 1 -a ! -e fam ]
# The checkpoint is append-only (src/bake/checkpoint.c): bytes after its counted
# records (an append cut short by the kill) are ignored; a changed byte inside
# a counted record is refused.
cp fam.checkpoint bad.checkpoint
printf 'torn append' >> fam.checkpoint
printf 'X' | dd of=bad.checkpoint bs=1 seek=200 conv=notrunc 2>/dev/null
"$B" bake $F $V --out bad --resume 2> err.txt
check "family: a changed byte in a saved member: exit 2" [ $? -eq 2 ]
check "family: ... saying its records are inconsistent" grep -q "bad.checkpoint: its records are inconsistent" err.txt
"$B" bake $F $V --out fam 2> err.txt
check "family: a stale checkpoint without --resume: exit 2" [ $? -eq 2 ]
check "family: ... and the message says to pass --resume or remove it" grep -q "fam.checkpoint.*--resume.*remove" err.txt
check "family: ... and no output" [ ! -e fam ]
"$B" bake $F --vary dermis.blood=0.01:0.06:3:lin --out fam --resume 2> err.txt
check "family: --resume with another --vary range: exit 2 (another bake)" [ $? -eq 2 ]
check "family: ... naming the checkpoint" grep -q "fam.checkpoint was written by a different bake" err.txt
"$B" bake $F $V --out fam --resume 2> err.txt
check "family: --resume" [ $? -eq 0 ]
check "family: ... says what it restored" grep -q "resuming from fam.checkpoint: 1 member finished" err.txt
check "family: resumed directory equals the uninterrupted one (its checkpoint had a torn append)" \
	resume_same ref fam checksums
check "family: ... whose members differ (the comparison can fail)" differ ref/m0000/brdf.exr ref/m0002/brdf.exr
check "family: the checkpoint is gone after the bake" [ ! -e fam.checkpoint ]

MPI="$top_builddir/skinbake-mpi"
if command -v mpirun >/dev/null 2>&1 && [ -x "$MPI" ]; then
	mpirun --allow-run-as-root -np 2 "$MPI" bake $F $V --out mpi --resume >/dev/null 2> err.txt
	check "family: --resume under MPI: exit 2" [ $? -eq 2 ]
	check "family: ... saying it works in one process only" grep -q "one process only" err.txt
	check "family: ... and no output" [ ! -e mpi ]
else
	skip "family: --resume under MPI (no mpirun)"
	skip "family: ... saying it works in one process only"
	skip "family: ... and no output"
fi
tap_done
