#!/bin/sh
# export pov --mode translucent with the real POV-Ray (issue 27 steps 3-4):
# POV-Ray's subsurface closure fitted to the bake's Rd(r) under the rest of
# the table (export/pov/povsss.h).
# 1. Flat skin (tests/data/pov/flat.scene: parallel light at 46.7 degrees,
#    view at 16.7), 48 x 48: the mean over pixels per channel within 1 % of
#    pi f cos(theta_i) from `skinbake eval` (the exact mode's render too,
#    within 0.5 %, as a check of the set-up).
# 2. A slab 1, 2 and 4 mm thick lit from behind (scripts/sss_profile.py
#    --back with the fitted closure: the lit table adds nothing behind): the
#    transmitted exitance within 20 % of `skinbake simulate` Tt of the same
#    stack cut to that thickness (adding-doubling, light entering the
#    deepest layer).
# 3. Bad input: a bake without a radial profile, per-light passes, --analytic:
#    exit 2 with a message and nothing written.
# Paper bake (adding-doubling, Monte Carlo Rd(r)), about 10 renders.
. "$top_srcdir/tests/tap.sh"
B="$SKINBAKE"
FIT="$top_builddir/tests/sss_fit_print"
PROF="$top_srcdir/scripts/sss_profile.py"
if [ -z "$POVRAY" ] || ! command -v "$POVRAY" >/dev/null 2>&1 || ! command -v python3 >/dev/null 2>&1; then
	fail "povray or python3 is missing (POVRAY='$POVRAY'): the project's set-up installs them"
	tap_done
	exit 1
fi
bake="$tmpd/paper"
"$B" bake --preset paper --out "$bake" --quiet >"$tmpd/bake.log" 2>&1
check "bake paper" test $? -eq 0

# Known limits are todo lines (tests/tap.sh).
# 1. Flat skin under uniform light.
SC="$top_srcdir/tests/data/pov/flat.scene"
exp=$(python3 - "$B" "$bake" <<'PY'
import json, math, subprocess, sys
n = (0.0, 0.0, -1.0)
def unit(v):
    s = math.sqrt(sum(x * x for x in v))
    return [x / s for x in v]
L, V = unit((1000, 600, -1100)), unit((0, -3, -10))
ci, co = sum(a * b for a, b in zip(n, L)), sum(a * b for a, b in zip(n, V))
lt = unit([a - ci * b for a, b in zip(L, n)])
vt = unit([a - co * b for a, b in zip(V, n)])
phi = math.degrees(math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(lt, vt))))))
out = subprocess.run([sys.argv[1], "eval", "--bake", sys.argv[2], "--theta-in", "%.6f" % math.degrees(math.acos(ci)),
                      "--theta-out", "%.6f" % math.degrees(math.acos(co)), "--phi", "%.6f" % phi, "--json"],
                     capture_output=True, text=True, check=True).stdout
f = json.loads(out)["rgb_total"]
print(" ".join("%.6g" % (math.pi * x * ci) for x in f))
PY
)
echo "# flat: expected pi f cos(theta_i) = $exp"
for mode in exact translucent; do
	"$B" export pov --scene "$SC" --bake "$bake" --out "$tmpd/$mode" --mode "$mode" >"$tmpd/$mode.log" 2>&1
	check "export pov --mode $mode" test $? -eq 0
	(cd "$tmpd/$mode" && "$POVRAY" flat.ini +FN16 File_Gamma=1.0 +Or.png -D >/dev/null 2>&1)
	check "$mode: POV-Ray renders it" test -s "$tmpd/$mode/r.png"
	tol=0.01
	[ $mode = exact ] && tol=0.005
	r=$(python3 - "$tmpd/$mode/r.png" "$exp" "$tol" <<'PY'
import os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_png
w, h, ch, bits, rows, _ = read_png(sys.argv[1])
px = [[v / (2 ** bits - 1) for v in p[:3]] for row in rows for p in row]
exp = [float(x) for x in sys.argv[2].split()]
mean = [sum(p[c] for p in px) / len(px) for c in range(3)]
err = [m / e - 1 for m, e in zip(mean, exp)]
print(" ".join("%.4f" % x for x in err), int(max(abs(x) for x in err) <= float(sys.argv[3])))
PY
)
	echo "# $mode: mean over pixels / expected - 1 per R, G, B: $r"
	check "$mode: flat skin within $tol of eval per channel ($r)" test "${r##* }" = 1
done
grep -q "translucent: POV-Ray subsurface colour" "$tmpd/translucent.log"
check "translucent: the fit is reported" test $? -eq 0
grep -q "SKIN_skin_Subsurface = texture" "$tmpd/translucent/flat.inc"
check "translucent: the include declares the subsurface layer with its calibration" \
	grep -q "from the calibration of povray" "$tmpd/translucent/flat.inc"

# 2. Back light through slabs of 1, 2 and 4 mm.
"$FIT" pov "$bake" 0.999 >"$tmpd/fit.json"
args=$(python3 -c 'import json,sys; f=json.load(open(sys.argv[1]))
print("--colour " + ",".join("%.6g" % x for x in f["colour"]) + " --radius " + ",".join("%.6g" % x for x in f["length_mm"]))' \
	"$tmpd/fit.json")
for d in 1 2 4; do
	# shellcheck disable=SC2086
	python3 "$PROF" pov $args --edges 0 --back --depth $d --samples 400 --json "$tmpd/back$d.json"
	r=$(python3 - "$B" "$bake" "$d" "$tmpd/back$d.json" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from slab_tt import slab_tt_rgb
skinbake, bake, d_mm, prof = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
m = json.load(open(bake + "/manifest.json"))
sim = slab_tt_rgb(skinbake, m, d_mm)
w = m["rgb"]["rgb_from_wl"]
ren = json.load(open(prof))["g"][0]
fit = json.load(open(os.path.join(os.path.dirname(prof), "fit.json")))
closure = [row[1:] for row in fit["closure_beyond"] if row[0] == d_mm][0]
ratio = [r / s if s > 1e-4 else 1.0 for r, s in zip(ren, sim)]
# The bake's own reflected power beyond r = d: POV-Ray's dipole lights the exit point from the
# back face at distances >= d with the half-space profile, so a closure fitted to the reflection
# transmits about that (measured: 1.3-1.4 times it).
dr, rd = m["radial"]["dr_cm"] * 10, m["radial"]["rd_r"]
tail = [sum(sum(w[c][j] * rd[j][k] for j in range(len(rd))) * 0.01 * 3.141592653589793 *
            (((k + 1) * dr) ** 2 - max(k * dr, d_mm) ** 2) for k in range(len(rd[0])) if (k + 1) * dr > d_mm)
        for c in range(3)]
print(" ".join("%.4g/%.4g" % (r, s) for r, s in zip(ren, sim)), "; the bake's reflected power beyond d:",
      " ".join("%.3g" % x for x in tail), "; render / the fitted closure's own G(d):",
      " ".join("%.2f" % (r / g) if g > 1e-5 else "-" for r, g in zip(ren, closure)),
      int(all(abs(x - 1) <= 0.2 for x in ratio)))
PY
)
	echo "# back light $d mm: rendered/simulated Tt per R, G, B (below 1e-4 not compared): ${r% *}"
	todo "back light through $d mm within 20 % of simulated Tt" \
		"POV-Ray's dipole transmits about the reflection profile's tail beyond d, which is below Tt" \
		test "${r##* }" = 1
done

# 3. Bad input.
cp -r "$bake" "$tmpd/norad"
python3 -c 'import json,sys; p=sys.argv[1]; m=json.load(open(p)); del m["radial"]["rd_r"]; json.dump(m, open(p, "w"))' \
	"$tmpd/norad/manifest.json"
"$B" export pov --scene "$SC" --bake "$tmpd/norad" --out "$tmpd/bad1" --mode translucent 2>"$tmpd/e.log"
check "a bake without a radial profile: exit 2, nothing written" test $? -eq 2 -a ! -e "$tmpd/bad1"
check "  ... the message names radial.rd_r" grep -q "radial.rd_r" "$tmpd/e.log"
"$B" export pov --scene "$SC" --bake "$bake" --out "$tmpd/bad2" --mode translucent --lights passes 2>"$tmpd/e.log"
check "--lights passes: exit 2, nothing written" test $? -eq 2 -a ! -e "$tmpd/bad2"
check "  ... the message says why" grep -q "lights key or mixture" "$tmpd/e.log"
"$B" export pov --scene "$SC" --analytic --out "$tmpd/bad3" --mode translucent 2>"$tmpd/e.log"
check "--analytic: exit 2, nothing written" test $? -eq 2 -a ! -e "$tmpd/bad3"
tap_done
