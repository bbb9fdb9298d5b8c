#!/bin/sh
# export pov --mode translucent on meshes lit from behind, with the real
# POV-Ray (issue 27, export/pov/povback.h): a closed slab mesh 1, 2 and 4 mm
# thick, 60 mm wide, units mm, a parallel light of colour 1 straight onto
# its back face, an orthographic camera straight at its front face (4 mm of
# its middle): the mean pixel (pi x radiance, the transmitted exitance for
# a Lambertian exit) within 10 % per channel of `skinbake simulate` Tt of the
# bake's stack cut to that thickness (tests/lib/slab_tt.py; the issue asks
# 20 %).  Then the same slab 20 mm thick lit from the front at 46.7 degrees:
# the back-light copy is empty there, and the mean within 1 % of pi f
# cos(theta_i) from `skinbake eval` (flat skin under uniform light).
# Last, the default --mode auto: translucent on the mesh, exact with a fill.
# Paper bake (adding-doubling), 4 renders of 16 x 16 pixels, 6 exports.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/pov.sh"
B="$SKINBAKE"
pov_require
bake="$tmpd/paper"
"$B" bake --preset paper --out "$bake" --quiet >"$tmpd/bake.log" 2>&1
check "bake paper" test $? -eq 0
# scene D LIGHT_POSITION COLOUR: a slab D mm thick with one parallel light.
scene() {
	python3 "$top_srcdir/tests/lib/slab_obj.py" "$1" 30 6 "$tmpd/slab$1.obj"
	cat <<EOS
[scene]
width = 16
height = 16
unit_mm = 1
[camera]
type = orthographic
location = 0 0 -100
look_at = 0 0 0
width = 4
[light back]
type = parallel
position = $2
color = $3
[skin skin]
preset = paper
[object slab]
shape = mesh
file = $tmpd/slab$1.obj
EOS
}
# render DIR BASE: DIR/BASE.pov -> DIR/r.png, 16 x 16, linear (POV-Ray warns that its
# subsurface transport is experimental, so not tests/lib/pov.sh's pov_render).
render() {
	(cd "$1" && "$POVRAY" "+I$2.pov" +Or.png +W16 +H16 -D -A +FN16 File_Gamma=1.0 >pov.log 2>&1)
}
# mean DIR: the mean pixel of DIR/r.png per R, G, B.
mean() {
	python3 - "$1/r.png" <<'PY'
import os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_png
w, h, ch, bits, rows, _ = read_png(sys.argv[1])
px = [[v / (2 ** bits - 1) for v in p[:3]] for row in rows for p in row]
print(" ".join("%.6g" % (sum(p[c] for p in px) / len(px)) for c in range(3)))
PY
}
for mm in 1 2 4; do
	# The light's colour per channel 0.5 / Tt (at most 1e6, the scene's limit): every
	# channel's pixel well above the 16-bit step; all of it is linear in the colour.  A
	# channel whose Tt is below 1e-5 (blue through 4 mm; slab_tt reads 6 decimals) is not compared.
	sim=$(python3 - "$B" "$bake" "$mm" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from slab_tt import slab_tt_rgb
print(" ".join("%.6g" % x for x in slab_tt_rgb(sys.argv[1], json.load(open(sys.argv[2] + "/manifest.json")),
                                                float(sys.argv[3]))))
PY
)
	col=$(python3 -c 'import sys; print(" ".join("%.6g" % min(1e6, 0.5 / max(float(x), 1e-12)) for x in sys.argv[1:]))' \
	    $sim)
	scene $mm "0 0 1000" "$col" >"$tmpd/back$mm.scene"
	"$B" export pov --scene "$tmpd/back$mm.scene" --bake "$bake" --out "$tmpd/back$mm" --mode translucent \
	    >"$tmpd/back$mm.log" 2>&1
	check "export pov --mode translucent, slab $mm mm" test $? -eq 0
	check "  ... the back-light copy is written" grep -q "the back light through its thin parts" \
	    "$tmpd/back$mm/back$mm.pov"
	render "$tmpd/back$mm" "back$mm"
	check "  ... POV-Ray renders it" test -s "$tmpd/back$mm/r.png"
	m=$(mean "$tmpd/back$mm")
	r=$(python3 - "$m" "$col" "$sim" <<'PY'
import sys
ren, col, sim = ([float(x) for x in a.split()] for a in sys.argv[1:4])
ratio = [r / c / s if s >= 1e-5 else None for r, c, s in zip(ren, col, sim)]
print(" ".join("%.4g/%.4g=%s" % (r / c, s, "%.3f" % q if q else "-") for r, c, s, q in zip(ren, col, sim, ratio)),
      int(all(abs(q - 1) <= 0.1 for q in ratio if q)))
PY
)
	echo "# back light $mm mm: rendered/simulated Tt per R, G, B: ${r% *}"
	check "back light through $mm mm within 10 % of simulated Tt per channel" test -n "$r" -a "${r##* }" = 1
done

# Flat skin under uniform light: the slab 20 mm thick lit from the front.
scene 20 "1000 600 -1100" "1 1 1" >"$tmpd/front.scene"
exp=$(python3 - "$B" "$bake" <<'PY'
import json, math, subprocess, sys
L = [1000, 600, -1100]
s = math.sqrt(sum(x * x for x in L))
ci = 1100 / s
phi = 180.0   # the view is the normal: any azimuth
out = subprocess.run([sys.argv[1], "eval", "--bake", sys.argv[2], "--theta-in", "%.6f" % math.degrees(math.acos(ci)),
                      "--theta-out", "0", "--phi", "%g" % phi, "--json"], capture_output=True, text=True,
                     check=True).stdout
print(" ".join("%.6g" % (math.pi * x * ci) for x in json.loads(out)["rgb_total"]))
PY
)
"$B" export pov --scene "$tmpd/front.scene" --bake "$bake" --out "$tmpd/front" --mode translucent \
    >"$tmpd/front.log" 2>&1
check "export pov --mode translucent, front-lit slab 20 mm" test $? -eq 0
check "  ... no vertex lit through" grep -q "0 of .* vertices lit through" "$tmpd/front/front.pov"
render "$tmpd/front" front
m=$(mean "$tmpd/front")
r=$(python3 -c 'import sys
m = [float(x) for x in sys.argv[1].split()]
e = [float(x) for x in sys.argv[2].split()]
err = [a / b - 1 for a, b in zip(m, e)]
print(" ".join("%.4f" % x for x in err), int(max(abs(x) for x in err) <= 0.01))' "$m" "$exp")
echo "# front light: mean / (pi f cos theta_i from eval) - 1 per R, G, B: ${r% *}"
check "flat mesh under uniform light within 1 % of eval per channel" test "${r##* }" = 1
# The default, --mode auto: translucent on this mesh; exact with a fill, saying why.
"$B" export pov --scene "$tmpd/back1.scene" --bake "$bake" --out "$tmpd/auto" >"$tmpd/auto.log" 2>&1
check "--mode auto (the default) on a mesh: translucent, with the back-light copy" \
    sh -c "grep -q \"translucent (--mode auto\" '$tmpd/auto.log' && grep -q 'lit through' '$tmpd/auto/back1.pov'"
sed 's/^unit_mm = 1$/unit_mm = 1\nfill = 0.1 0.1 0.1/' "$tmpd/back1.scene" >"$tmpd/fill.scene"
"$B" export pov --scene "$tmpd/fill.scene" --bake "$bake" --out "$tmpd/fill" >"$tmpd/fill.log" 2>&1
check "--mode auto with a fill: exact, and the export says why" \
    sh -c "grep -q 'exact (--mode auto: the scene has a fill)' '$tmpd/fill.log' && ! grep -q 'lit through' '$tmpd/fill/fill.pov'"
tap_done
