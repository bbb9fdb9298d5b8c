#!/bin/sh
# The relief's far roughness in POV-Ray (issue 24 item 3, docs/relief.md section 6): the sphere of
# scenes/sphere.scene 100 mm across, 1.7 mm per pixel, so the face relief's 0.35 mm cells are below
# a pixel.  The export then drops the bump map and blends the lit table with its rough copy by
# roughness_far.png (src/export/pov/povfar.h).  Checks: a flat relief (alpha_relief 0) writes no far
# map and renders exactly as no textures at all; the face relief writes the map and the rough table,
# its highlight is lower than the flat relief's, its mean no brighter and at most as much darker
# as the ring's tilted facets lose; at the
# scene's own size (0.17 mm per pixel) the bump map stays.  About 15 s.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/relief.sh"
. "$top_srcdir/tests/lib/pov.sh"
pov_require

relief_bake
relief_textures 256
sed 's/^unit_mm = 10$/unit_mm = 100/' "$top_srcdir/scenes/sphere.scene" >"$tmpd/far.scene"
for t in face flat none; do
	a="--textures $tmpd/tex-$t"
	[ $t = none ] && a=
	# shellcheck disable=SC2086
	"$SKINBAKE" export pov --scene "$tmpd/far.scene" --bake "$bake" $a --out "$tmpd/$t" >"$tmpd/$t.log" 2>&1
	check "export, $t relief" test $? -eq 0
	pov_render "$tmpd/$t" far 64 64
	check "render, $t relief" test $? -eq 0
done
check "flat relief: no far map, no rough table" \
	sh -c "! ls '$tmpd/flat' | grep -q roughness_far && ! grep -q _Rough '$tmpd/flat/far.inc'"
check "face relief: far map and rough table written, and said" \
	sh -c "test -f '$tmpd/face/far_skin_roughness_far.png' && grep -q 'SKIN_skin_Pigment_Rough scale' \
'$tmpd/face/far.inc' && grep -q 'gives way to the table blended' '$tmpd/face.log'"
out=$(python3 - "$tmpd" <<'PY'
import os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_png
d = sys.argv[1]
def grey(t):
    w, h, ch, bits, rows, text = read_png(os.path.join(d, t, "r.png"))
    return [sum(p[:3]) / 3 / 65535 for row in rows for p in row]
a, b, f = grey("flat"), grey("none"), grey("face")
mask = [i for i, v in enumerate(b) if v > 1e-3]
diff = max(abs(a[i] - b[i]) for i in range(len(a)))
mean = lambda x: sum(x[i] for i in mask) / len(mask)
p995 = lambda x: sorted(x[i] for i in mask)[int(0.995 * (len(mask) - 1))]
print("%.3g %.4f %.4g %.4g %d" % (diff, mean(f) / mean(a) - 1, p995(f), p995(a), len(mask)))
PY
)
set -- $out
if [ $# -eq 5 ] && [ "$1" = 0 ]; then
	ok "flat relief renders exactly as no textures ($5 px)"
else
	fail "flat relief vs no textures: '$out'"
fi
# A ring of normals tilted by alpha_max receives (L.m) on facets whose projected area is cos t of
# theirs: a Lambert surface is darker by up to 1 - 1/sqrt(1 + alpha_max^2), which the bump map
# loses as well; brighter it must not be (2 % for the table's interpolation).
amax=$(sed -n 's/.*alpha_relief up to \([0-9.e+-]*\)).*/\1/p' "$tmpd/face.log")
if [ $# -eq 5 ] && [ -n "$amax" ] &&
    awk -v m="$2" -v a="$amax" 'BEGIN { exit !(m < 0.02 && m > -(1 - 1 / sqrt(1 + a * a))) }'; then
	ok "face relief far: mean brightness $2 relative to the flat relief's (alpha_max $amax)"
else
	fail "face relief far: mean vs flat: '$out', alpha_max '$amax'"
fi
if [ $# -eq 5 ] && awk -v a="$3" -v b="$4" 'BEGIN { exit !(a < 0.95 * b) }'; then
	ok "face relief far: highlight (99.5th percentile $3) below the flat relief's ($4)"
else
	fail "face relief far: highlight vs flat: '$out'"
fi
"$SKINBAKE" export pov --scene "$top_srcdir/scenes/sphere.scene" --bake "$bake" --textures "$tmpd/tex-face" \
	--out "$tmpd/near" >"$tmpd/near.log" 2>&1
check "near (0.17 mm per pixel): the bump map stays, no far map" \
	sh -c "grep -q bump_map '$tmpd/near/sphere.inc' && ! grep -q _Rough '$tmpd/near/sphere.inc'"
tap_done
