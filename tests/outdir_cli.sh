#!/bin/sh
# Every writer writes only into a new directory or one holding a complete
# output of its own kind (issue 23 item 1, src/base/outdir.c): a user's
# files, another kind's output, '/', a dangling link and the command's own
# inputs are refused with exit status 2 and a message saying why, before
# any work, and nothing in them changes.  A second writer of one output is
# refused naming the first (item 3), also `bake --resume` of a live bake.
# Costs about 10 s.
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
T=$top_srcdir
cd "$tmpd" || exit 1
BK="--preset paper --solver ad --theta-nodes 3 --resolution 9x6 --radial-error 0.2 --r-bins 20 --quiet"
LUT="--lut-cos 8 --lut-phi 3"


# bad DESC PATTERN DIR CMD...: exit 2, stderr matches PATTERN (grep -E), DIR unchanged
# (tests/lib/refused.sh)
. "$top_srcdir/tests/lib/refused.sh"
refused_ere=1
bad() {
	b_d=$1 b_p=$2 refused_kept=$3
	shift 3
	refused "$b_d" "$b_p" "" "$@"
	refused_kept=
}

$B bake $BK --out bk || fail "good bake"
$B texture --size 16 --out tx --quiet || fail "good texture"
$B export blender --bake bk --textures tx --out bl $LUT > /dev/null || fail "good image set"
$B export pov --bake bk --scene "$T/scenes/sphere.scene" --out pv > /dev/null 2>&1 || fail "good POV-Ray export"
$B bake --preset paper --solver ad --theta-nodes 2 --resolution 3x3 --radial-error 0.3 --r-bins 10 \
	--vary dermis.blood=0.01:0.03:2 --out fam --quiet || fail "good family"

# ---- user files
mkdir user && echo '{"mine": 1}' > user/manifest.json && echo letter > user/letter.txt
bad "bake --out a directory with the user's own manifest.json" "user holds manifest.json, but not of a bake" user \
	$B bake $BK --out user
mkdir home && echo letter > home/letter.txt
bad "texture --out a directory of the user's files" "home is a directory without manifest.json" home \
	$B texture --size 16 --out home --quiet
cp -r bk bk_notes && echo mine > bk_notes/notes.txt
bad "bake --out a complete bake plus a user's file" "holds 'notes.txt', which is not part of a bake directory" \
	bk_notes $B bake $BK --out bk_notes
cp -r bl bl_notes && echo mine > bl_notes/photo.png
bad "export blender --out an image set plus a user's image" "holds 'photo.png'" bl_notes \
	$B export blender --bake bk --out bl_notes $LUT

# ---- another kind's output
bad "export blender --bake bk --out bk" "bk is also an input|not of a Blender image set" bk \
	$B export blender --bake bk --out bk $LUT
bad "texture --out BAKE" "bk holds manifest.json, but not of a texture directory" bk \
	$B texture --size 16 --out bk --quiet
bad "export blender --textures tx --out tx" "tx is also an input|not of a Blender image set" tx \
	$B export blender --bake bk --textures tx --out tx $LUT
bad "export pov --out BAKE" "bk is also an input|not of a POV-Ray export" bk \
	$B export pov --bake bk --scene "$T/scenes/sphere.scene" --out bk
bad "bake --out a family" "fam is a directory without manifest.json, not a bake directory" fam \
	$B bake $BK --out fam
bad "bake --vary --out a bake" "bk is a directory without family.json" bk \
	$B bake --preset paper --solver ad --theta-nodes 2 --resolution 3x3 --vary dermis.blood=0.01:0.03:2 --out bk --quiet
bad "maps new --out an image set" "not a maps directory|without maps.json" bl \
	$B maps new --family fam --set dermis.blood=0.02 --size 8x8 --out bl --quiet
bad "export pov --out an image set" "not of a POV-Ray export" bl \
	$B export pov --bake bk --scene "$T/scenes/sphere.scene" --out bl

# ---- inputs
bad "export blender --out inside its input" "bk/sub is inside the input bk" bk \
	$B export blender --bake bk --out bk/sub $LUT
bad "maps new --out inside the family" "fam/mp is inside the input fam" fam \
	$B maps new --family fam --set dermis.blood=0.02 --size 8x8 --out fam/mp --quiet

# ---- '/', a dangling link (refused before the bake, not after it)
for cmd in "bake $BK" "texture --size 16 --quiet"; do
	bad "${cmd%% *} --out /" "cannot replace this directory as a whole" bk $B $cmd --out /
done
ln -s nowhere dangling
bad "bake --out a dangling symbolic link" "dangling is a symbolic link to a directory that does not exist" bk \
	$B bake $BK --out dangling

# ---- an output of the same kind is replaced
check "bake --out an earlier bake" $B bake $BK --out bk
check "export pov --out an earlier export (its manifest lists the files)" \
	sh -c "'$B' export pov --bake bk --scene '$T/scenes/sphere.scene' --out pv > /dev/null 2>&1 && test -f pv/manifest.json"
check "export blender --out an earlier image set" sh -c "'$B' export blender --bake bk --out bl $LUT > /dev/null"

# ---- a second writer (item 3): refused naming the first, also with --resume
$B bake --preset paper --solver mc --theta-nodes 2 --resolution 3x3 --r-bins 10 --max-photons 1e12 --target-error 0.001 \
	--checkpoint-seconds 0 --out slow --quiet 2> slow.err &
first=$!
i=0
while [ ! -e .slow.lock ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
if [ -e .slow.lock ]; then
	bad "a second bake on a directory being baked" "slow is being written by process $first \(.*bake.*\)" bk \
		$B bake $BK --out slow
	sleep 0.5
	bad "bake --resume of a bake that is still running" "slow is being written by process $first" bk \
		$B bake $BK --out slow --resume
else
	fail "the first bake did not take its lock: $(cat slow.err)"
fi
kill $first 2> /dev/null
wait $first 2> /dev/null
rm -f slow.checkpoint	# the killed bake's, of another spec
ln -s /dev/zero zero.checkpoint
bad "bake --resume with /dev/zero as its checkpoint (once read without end)" \
	"zero.checkpoint is not a regular file" bk timeout 60 $B bake $BK --out zero --resume
check "after the first writer is gone its lock is free, its staging removed" \
	sh -c "'$B' bake $BK --out slow && [ -z \"\$(ls -A | grep '^\.slow\.')\" ]"
tap_done
