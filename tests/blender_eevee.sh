#!/bin/sh
# The exact mode in EEVEE (headless: software EGL, Mesa llvmpipe) against Cycles on a sphere: no
# seams where brdf_lut.exr's tiles meet (they were up to 28 % off), within 2 % per 2 x 2 pixel
# block; and a lit world is refused with exit status 2.  About 40 s, most of it EEVEE compiling
# the node tree.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/blender.sh"

imp="$top_srcdir/exporters/blender/import_skin.py"
scn="$top_srcdir/tests/blender_scene.py"
blender_require
bake="$tmpd/bake"
if ! "$SKINBAKE" bake --preset paper --out "$bake" --theta-nodes 6 --resolution 9x9 --batch-photons 1000 \
	--max-photons 3e5 --target-error 0 --threads 1 --quiet >"$tmpd/bake.log" 2>&1; then
	fail "skinbake bake failed: $(tail -2 "$tmpd/bake.log")"
	tap_done
	exit 1
fi
"$SKINBAKE" export blender --bake "$bake" --out "$tmpd/set" --mode exact >"$tmpd/export.log" 2>&1
for e in CYCLES BLENDER_EEVEE; do
	B --python "$imp" -- "$tmpd/set" --mode exact --scene sphere --engine $e --res 64 --samples 16 \
		--render "$tmpd/$e.exr" >"$tmpd/$e.log" 2>&1
	check "exact sphere renders in $e ($(sed -n 's/^SKINBAKE_RENDER_SECONDS //p' "$tmpd/$e.log") s)" test $? -eq 0
done
B --python "$scn" -- blocks "$tmpd/BLENDER_EEVEE.exr" "$tmpd/CYCLES.exr" 2 0.05 >"$tmpd/blk.log" 2>&1
set -- $(sed -n 's/^SKINBAKE_BLOCKS //p' "$tmpd/blk.log")
if [ $# -eq 3 ] && awk -v n="$1" -v m="$2" -v x="$3" 'BEGIN { exit !(n >= 200 && m < 0.02 && x < 0.05) }'; then
	ok "EEVEE vs Cycles, exact mode: $1 blocks of 2x2 px, mean $2, max $3 (no seams)"
else
	fail "EEVEE vs Cycles, exact mode: '$*'"
fi
B --python "$imp" -- "$tmpd/set" --mode exact --scene sphere --engine BLENDER_EEVEE --world 0.05 \
	--render "$tmpd/never.exr" >"$tmpd/w.log" 2>&1
rc=$?
if [ $rc -eq 2 ] && grep -q "import_skin.py: error: exact mode in EEVEE needs a black world" "$tmpd/w.log" &&
    [ ! -e "$tmpd/never.exr" ]; then
	ok "EEVEE exact mode with a lit world: exit 2, '$(grep 'import_skin.py: error' "$tmpd/w.log" | cut -c1-90)...'"
else
	fail "EEVEE exact mode with a lit world: rc $rc, $(tail -2 "$tmpd/w.log")"
fi
tap_done
