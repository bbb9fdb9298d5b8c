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

scene none 0 skin
"$SKINBAKE" export pov --scene "$tmpd/none.scene" --bake "$B" --out "$tmpd/none" >/dev/null 2>"$tmpd/none.err"
check "fill_occlusion = 0: no map, the plain fill" sh -c "! ls '$tmpd/none' | grep -q _ao_ && ! grep -q _ao_ '$tmpd/none/none.pov'"

scene bad 1.5 skin
refused "fill_occlusion = 1.5 is refused" "fill_occlusion = 1.5" "$tmpd/bad" \
	"$SKINBAKE" export pov --scene "$tmpd/bad.scene" --bake "$B" --out "$tmpd/bad"
tap_done
