#!/bin/sh
# Silhouettes of a POV-Ray render against adding-doubling itself (issue 26):
# a default adding-doubling bake of `paper` (9 x 9, incidence nodes to
# 86.6 deg), the sphere scene exported and rendered by the real POV-Ray
# (128 x 128, 16-bit linear), and tests/pov_compare's expected values from
# adding-doubling point values of the bake's own layer stacks at each
# pixel's angles (not from eval, which the render follows by
# construction), on the pixels whose exit angle is 70 deg or more, the
# grazing ring.  Measured: 0.13 % mean relative error (eval's own
# comparison over the whole sphere: 0.14 %); a bake with --theta-nodes 4
# (linear in theta_i between 0, 22.5, 45 and 67.5 deg) is 6 % off there.
# About 10 s.
. "$top_srcdir/tests/tap.sh"
CMP="$top_builddir/tests/pov_compare"
SC="$top_srcdir/scenes"
. "$top_srcdir/tests/lib/pov.sh"
pov_require
B="$tmpd/bake"
check "default adding-doubling bake of paper (9 x 9)" "$SKINBAKE" bake --preset paper --out "$B" --resolution 9x9 \
	--r-bins 20 --radial-photons 4000 --quiet
check "the bake holds point values" python3 -c "
import json; m=json.load(open('$B/manifest.json')); assert m['table']['values']==['points']*3"
check "export pov (sphere)" "$SKINBAKE" export pov --out "$tmpd/sphere" --data-dir "$top_srcdir/exporters/pov" \
	--scene "$SC/sphere.scene" --bake "$B"
check "POV-Ray renders the sphere" pov_render "$tmpd/sphere" sphere 128 128
r=$("$CMP" expect --scene "$SC/sphere.scene" --bake "$B" --render "$tmpd/sphere/r.png" --ad --min-theta-out 70 \
	--tol 0.005)
rc=$?
check "silhouettes (exit >= 70 deg) against adding-doubling point values: $(echo "$r" | tr '\n' ' ') (<= 0.5 %)" \
	test $rc -eq 0
tap_done
