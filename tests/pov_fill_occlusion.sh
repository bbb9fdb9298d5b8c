#!/bin/sh
# The fill's occlusion (`fill_occlusion` in [scene], export/pov/povao.h) against the view factor:
# a floor (tests/data/mesh/floor-ceiling.obj, side 4, a vertex at its centre and four corners)
# under a parallel ceiling square of side 2 at height 1.  A vertex's visibility is 1 - F, F the
# view factor from a surface element to a parallel rectangle (Howell, A Catalog of Radiation Heat
# Transfer Configuration Factors, B-3, summed with signs over the rectangle's corners): 0.44587 at
# the centre, 0.97914 at each corner, mean 0.87249.  1024 rays per vertex: the mean's binomial
# standard error is 0.0035, so 0.011 (3 sigma; stratification only lowers it).  The map is written,
# the .pov multiplies the fill by it on `model` and skin meshes and POV-Ray renders both; 0 rays
# writes no map; a fractional count is refused.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/refused.sh"
. "$top_srcdir/tests/lib/pov.sh"
pov_require
FIX="$top_srcdir/tests/data/mesh/floor-ceiling.obj"

# scene NAME RAYS MATERIAL: $tmpd/NAME.scene, camera above the floor
scene() {
	{
		printf '[scene]\nwidth = 32\nheight = 32\nfill = 0.2 0.2 0.2\nfill_occlusion = %s\n' "$2"
		printf '[camera]\ntype = orthographic\nlocation = 0 10 -1\nlook_at = 0 0 0\nwidth = 6\n'
		printf '[light key]\ntype = parallel\nposition = 1000 3000 -400\ncolor = 0.8 0.8 0.8\n'
		printf '[skin skin]\npreset = paper\n'
		printf '[object floor]\nshape = mesh\nfile = %s\nmesh = floor\nmaterial = %s\n' "$FIX" "$3"
		printf '[object ceiling]\nshape = mesh\nfile = %s\nmesh = ceiling\nmaterial = model\n' "$FIX"
	} >"$tmpd/$1.scene"
}

B="$tmpd/bake"
check "small bake of preset paper" "$SKINBAKE" bake --preset paper --out "$B" --theta-nodes 4 --resolution 9x9 \
	--estimator bins --max-photons 1e6 --batch-photons 4000 --target-error 0 --quiet

scene model 1024 model
"$SKINBAKE" export pov --scene "$tmpd/model.scene" --bake "$B" --out "$tmpd/model" >/dev/null 2>"$tmpd/model.err"
v=$(sed -n 's/.*mean visibility \([0-9.]*\).*/\1/p' "$tmpd/model.err")
check "floor under a ceiling: mean visibility ${v:-none} within 0.011 of the view factor's 0.87249" \
	awk -v v="${v:--1}" 'BEGIN { d = v - 0.87249; exit !(d < 0.011 && d > -0.011) }'
check "the map model_ao_floor.png is written, the ceiling (no UVs) gets none" \
	sh -c "test -f '$tmpd/model/model_ao_floor.png' && ! test -f '$tmpd/model/model_ao_ceiling.png'"
check "model material: the .pov multiplies the fill by the map" grep -q 'png "model_ao_floor.png"' "$tmpd/model/model.pov"
check "model material: POV-Ray renders it" pov_render "$tmpd/model" model 32 32

scene skin 16 skin
"$SKINBAKE" export pov --scene "$tmpd/skin.scene" --bake "$B" --out "$tmpd/skin" >/dev/null 2>"$tmpd/skin.err"
check "skin: SKIN_skin_Fill_floor is declared and used" \
	sh -c "grep -q '#declare SKIN_skin_Fill_floor' '$tmpd/skin/skin.pov' && grep -q 'SKIN_skin_Fill_floor }' '$tmpd/skin/skin_mesh_floor.inc' '$tmpd/skin/skin.pov'"
check "skin: POV-Ray renders it" pov_render "$tmpd/skin" skin 32 32

# The occluded fill's low end: the fill bounced once off the skin, albedo(theta_o) x fill x A with
# A the white-sky albedo 2 int a(mu) mu dmu (export/pov/povsplit.h).  A camera between floor and
# ceiling looks at the floor's centre (V 0.446, in the key's shadow, so only the fill lights it), 11
# degrees off the normal.  Three renders of the same .pov: as written (P), the low end black (the
# old, grey occlusion: P0 = fill x a x V) and the low end the full fill (P1 = fill x a); the
# bounce's share (P - P0) / (P1 - P0) must be A per channel, A integrated here from the .inc's
# fill colour map (linear in theta between nodes, as the aoi pattern is).  16-bit pixels of
# about 0.01-0.04 give A to about 1e-3; 0.005 allowed.
{
	printf '[scene]\nwidth = 17\nheight = 17\nfill = 0.2 0.2 0.2\nfill_occlusion = 1024\n'
	printf '[camera]\ntype = orthographic\nlocation = 0 0.5 -0.1\nlook_at = 0 0 0\nwidth = 0.02\n'
	printf '[light key]\ntype = parallel\nposition = 1000 3000 -400\ncolor = 0.8 0.8 0.8\n'
	printf '[skin skin]\npreset = paper\n'
	printf '[object floor]\nshape = mesh\nfile = %s\nmesh = floor\nmaterial = skin\n' "$FIX"
	printf '[object ceiling]\nshape = mesh\nfile = %s\nmesh = ceiling\nmaterial = model\n' "$FIX"
} >"$tmpd/warm.scene"
"$SKINBAKE" export pov --scene "$tmpd/warm.scene" --bake "$B" --out "$tmpd/warm" >/dev/null 2>"$tmpd/warm.err"
check "skin: the occluded fill blends toward SKIN_skin_FillBounce, declared in the .inc" \
	sh -c "grep -q 'pigment_map { \[0 SKIN_skin_FillBounce\] \[1 SKIN_skin_Fill\] }' '$tmpd/warm/warm.pov' &&
		grep -q '#declare SKIN_skin_FillBounce = pigment { aoi' '$tmpd/warm/warm.inc'"
for v in bounce black full; do
	mkdir -p "$tmpd/w-$v"
	cp "$tmpd/warm/"* "$tmpd/w-$v/"
	case $v in
	black) sed -i 's/\[0 SKIN_skin_FillBounce\]/[0 rgb 0]/' "$tmpd/w-$v/warm.pov" ;;
	full) sed -i 's/\[0 SKIN_skin_FillBounce\]/[0 SKIN_skin_Fill]/' "$tmpd/w-$v/warm.pov" ;;
	esac
	check "warm occlusion, low end $v: POV-Ray renders it" pov_render "$tmpd/w-$v" warm 17 17
done
check "the bounce's share of the occluded fill is the white-sky albedo (R, G, B within 0.005)" python3 -c "
import math, re, sys
sys.path.insert(0, '$top_srcdir/tests/lib')
from images import read_png
inc = open('$tmpd/warm/warm.inc').read()
m = re.search(r'#declare SKIN_skin_Fill = pigment \{ aoi color_map \{(.*?)\} \}', inc)
ent = [(float(v), (float(r), float(g), float(b))) for v, r, g, b in
       re.findall(r'\[([0-9.]+) rgb <([-0-9.e]+),([-0-9.e]+),([-0-9.e]+)>\]', m.group(1))]
th = sorted((math.pi * (1 - v), c) for v, c in ent if v >= 0.5)
def a(t, c):
    if t <= th[0][0]: return th[0][1][c]
    for (t0, c0), (t1, c1) in zip(th, th[1:]):
        if t <= t1: return c0[c] + (t - t0) / (t1 - t0) * (c1[c] - c0[c])
    return th[-1][1][c]
n = 4000
A = [sum(a(math.acos((u + 0.5) / n), c) * 2 * (u + 0.5) / n / n for u in range(n)) for c in range(3)]
px = {}
for v in ('bounce', 'black', 'full'):
    w, h, ch, bits, rows, _ = read_png('$tmpd/w-%s/r.png' % v)
    px[v] = [x / 65535 for x in rows[h // 2][w // 2][:3]]
share = [(px['bounce'][c] - px['black'][c]) / (px['full'][c] - px['black'][c]) for c in range(3)]
V = px['black'][1] / px['full'][1]
print('# V %.4f; A (integrated) %s; bounce share (rendered) %s' % (V, ' '.join('%.4f' % x for x in A),
      ' '.join('%.4f' % x for x in share)))
sys.exit(not (0.3 < V < 0.6 and all(abs(share[c] - A[c]) < 0.005 for c in range(3))))
"

scene none 0 skin
"$SKINBAKE" export pov --scene "$tmpd/none.scene" --bake "$B" --out "$tmpd/none" >/dev/null 2>"$tmpd/none.err"
check "fill_occlusion = 0: no map, the plain fill" sh -c "! ls '$tmpd/none' | grep -q _ao_ && ! grep -q _ao_ '$tmpd/none/none.pov'"

scene bad 1.5 skin
refused "fill_occlusion = 1.5 is refused" "fill_occlusion = 1.5" "$tmpd/bad" \
	"$SKINBAKE" export pov --scene "$tmpd/bad.scene" --bake "$B" --out "$tmpd/bad"
tap_done
