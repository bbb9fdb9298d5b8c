#!/bin/sh
# export blender --family --maps --mode translucent with the real Blender (issue 27 items 2 and 4:
# the maps path carries the per-texel calibration; docs/maps.md, "Blender, translucent").
# A 3-member family over dermis.blood (0.005, 0.03, 0.1; adding-doubling, 7 wavelengths, Monte
# Carlo Rd(r) shared by the members) and regional maps: blood 0.03 (member m0001) on the box's
# +x half, 0.06 (between m0001 and m0002) on its -x half (a mask split at the top face's
# u = 0.75; 512 x 512 texels, 1.6 mm each on the 200 mm face).
# 1. Per-texel parameters: this Blender's node colour and radius (sss_colour_M.N.exr,
#    sss_radius_M.N.exr) in the 0.06 region against the fit of a single bake at blood 0.06
#    (tests/sss_fit_print cycles-M.N), within 3 sigma of the two profiles' Monte Carlo error
#    plus the bound of linear interpolation between the nodes (tests/lib/sss_texel.py); in the
#    0.03 region, member m0001's own fit (within 1e-5).
# 2. Flat, one sun, the importer's closed box in exact mode (sun 45 deg, view 30 deg, 96 px, 128
#    samples), each region's mean away from the boundary (8-19 mm from it; the red profile holds
#    about 99 % of its power within 5 mm): the translucent render at m0001's blood within 1 % of
#    E cos(theta_i) f from `skinbake eval` of m0001, and at 0.06 within 1 % of the exact-mode
#    render of the same maps (the family's table there: node + lambert_extra + remainder add up
#    to it per texel), on every Blender (4.x too: the albedo table, blender_sss_albedo.h).  The
#    exact render at m0001 within 0.5 % of eval checks the set-up.
# 3. Bad input: a family set whose translucent entry has no per-texel maps is refused, naming
#    translucent.versions[M.N].maps.
# Runs on $BLENDER (Debian's 3.4, or a bpy venv through tests/bpy-blender: tests/blender_matrix.sh
# runs it on 4.5 and 5.0).  About 3 minutes of CPU (the fits: about 8 s per member and version).
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/translucent_fit.sh"
imp="$top_srcdir/exporters/blender/import_skin.py"
FIT="$top_builddir/tests/sss_fit_print"
if [ -z "$BLENDER" ] || ! command -v "$BLENDER" >/dev/null 2>&1 || ! command -v python3 >/dev/null 2>&1; then
	fail "blender or python3 is missing (BLENDER='$BLENDER'): the project's set-up installs them"
	tap_done
	exit 1
fi
B() { timeout 900 "$BLENDER" -b --factory-startup -noaudio --python-exit-code 1 "$@"; }
blver=$(B --python-expr 'import bpy; print("BLVER %d.%d" % tuple(bpy.app.version[:2]))' \
	2>/dev/null | sed -n 's/^BLVER //p' | head -n 1)
echo "# Blender $blver ($BLENDER)"

fam="$tmpd/fam"
set -- --wavelengths 400:700:50 --theta-nodes 4 --resolution 9x9
check "family over dermis.blood" "$SKINBAKE" bake --preset fair-oily "$@" \
	--vary dermis.blood=0.005,0.03,0.1 --out "$fam" --quiet
printf '[skin]\nbase = fair-oily\n[dermis]\nblood = 0.06\n' >"$tmpd/b.ini"
check "single bake at dermis.blood = 0.06" "$SKINBAKE" bake --preset-file "$tmpd/b.ini" "$@" \
	--out "$tmpd/b006" --quiet

# The regional maps: the mask is 1 where u > 0.75 (columns 384-511), the box top's -x half.
python3 - "$tmpd/mask.png" <<'PY'
import struct, sys, zlib
w = h = 512
raw = b"".join(b"\0" + bytes(255 if x >= 384 else 0 for x in range(w)) for _ in range(h))
def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
open(sys.argv[1], "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                              + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
PY
"$SKINBAKE" maps new --family "$fam" --size 512x512 --set dermis.blood=0.03 --out "$tmpd/u" --quiet &&
	"$SKINBAKE" maps edit --maps "$tmpd/u" --set dermis.blood=0.06 --mask "$tmpd/mask.png" \
		--out "$tmpd/maps" --quiet
check "regional maps (blood 0.03 | 0.06)" test $? -eq 0
for mode in exact translucent; do
	"$SKINBAKE" export blender --family "$fam" --maps "$tmpd/maps" --out "$tmpd/set-$mode" \
		--mode "$mode" >"$tmpd/export-$mode.log" 2>&1
	check "export blender --family --maps --mode $mode" test $? -eq 0 -a -f "$tmpd/set-$mode/manifest.json"
done
set="$tmpd/set-translucent"

# A Blender without its own fit in the set is refused by the importer (tests/lib/translucent_fit.sh);
# everything below needs this version's fit.
if ! translucent_fit "$set" "$blver" "per-texel checks and renders"; then
	tap_done
	exit 0
fi
for m in 0 1 2; do "$FIT" "cycles-$blver" "$fam/m000$m" >"$tmpd/m$m.json"; done
"$FIT" "cycles-$blver" "$tmpd/b006" >"$tmpd/b006.json"
check "the members' and the single bake's fits for Cycles $blver" \
	test -s "$tmpd/m2.json" -a -s "$tmpd/b006.json"

# 1. Per-texel parameters (texel row 256; column 100: blood 0.03, column 450: blood 0.06).
r=$(python3 - "$set" "$blver" "$tmpd" "$fam" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_exr
from sss_texel import check
st, ver, d, fam = sys.argv[1:5]
v = [x for x in json.load(open(st + "/manifest.json"))["translucent"]["versions"] if x["blender"] == ver][0]
col, rad = read_exr(st + "/" + v["maps"]["colour"]["file"]), read_exr(st + "/" + v["maps"]["radius_m"]["file"])
def texel(x):
    return {"colour": [col[c][256][x] for c in "RGB"], "length_mm": [1e3 * rad[c][256][x] for c in "RGB"]}
members = [json.load(open(d + "/m%d.json" % m)) for m in range(3)]
ok, out = check(texel(450), json.load(open(d + "/b006.json")), members, fam, 0.06, fam + "/m0001", d + "/b006")
t1 = texel(100)
dev = max(abs(t1[k][c] / members[1][k][c] - 1) for k in ("colour", "length_mm") for c in range(3))
print("; ".join(out), "/ m0001 texel: %.2g" % dev, int(ok), int(dev < 1e-5))
PY
)
echo "# blood 0.06 texel / single bake's fit - 1: $(echo "$r" | sed 's/ [01] [01]$//')"
check "blood 0.06: the texel's node parameters match a single bake's fit" test "$(echo "$r" | awk '{print $(NF-1)}')" = 1
check "blood 0.03: the texel's node parameters are member m0001's fit" test "${r##* }" = 1

# 2. The box, exact mode, both sets; region means read back from the EXR.
for mode in exact translucent; do
	s=128
	[ $mode = exact ] && s=16
	B --python "$imp" -- "$tmpd/set-$mode" --mode exact --scene box --res 96 --samples $s \
		--render "$tmpd/box-$mode.exr" >"$tmpd/box-$mode.log" 2>&1
	check "$mode set: import and render the box" test $? -eq 0 -a -s "$tmpd/box-$mode.exr"
done
check "  ... the importer added this Blender's per-texel node" \
	grep -q "translucent: Cycles $blver.* per texel from sss_colour_$blver.exr" "$tmpd/box-translucent.log"
r=$(python3 - "$SKINBAKE" "$fam/m0001" "$tmpd/b006" "$set/manifest.json" "$tmpd" <<'PY'
import json, math, os, subprocess, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from images import read_exr
skinbake, m1, b006, man, d = sys.argv[1:6]
e = json.load(open(man))["exact"]
ref = e["reference"]
def want(bake):
    out = subprocess.run([skinbake, "eval", "--bake", bake, "--theta-in", "%.6f" % math.degrees(math.acos(ref["cos_light"])),
                          "--theta-out", "%.6f" % math.degrees(math.acos(ref["cos_view"])), "--phi",
                          "%.6f" % ref["delta_phi_deg"], "--json"], capture_output=True, text=True, check=True).stdout
    return [e["sun_strength_w_m2"] * ref["cos_light"] * x for x in json.loads(out)["rgb_total"]]
# 96 px over 40 mm (0.417 mm/px); screen right is +x.  Columns 67-92: x = +8..+19 mm (blood 0.03);
# 3-28: x = -19..-8 mm (blood 0.06); rows 8-87.
def region(img, x0, x1):
    return [sum(img[c][y][x] for y in range(8, 88) for x in range(x0, x1)) / (80 * (x1 - x0)) for c in "RGB"]
ex, tr = read_exr(d + "/box-exact.exr"), read_exr(d + "/box-translucent.exr")
w1, w6 = want(m1), want(b006)
rel = lambda a, b: [x / y - 1 for x, y in zip(a, b)]
e_a = rel(region(ex, 67, 93), w1)
t_a = rel(region(tr, 67, 93), w1)
t_b = rel(region(tr, 3, 29), region(ex, 3, 29))
info = rel(region(tr, 3, 29), w6)
f = lambda v: " ".join("%+.4f" % x for x in v)
lim = lambda v, t: int(max(abs(x) for x in v) <= t)
print("%s | %s | %s | %s" % (f(e_a), f(t_a), f(t_b), f(info)),
      lim(e_a, 0.005), lim(t_a, 0.01), lim(t_b, 0.01))
PY
)
nums=${r% * * *}
flags=${r#"$nums" }
echo "# box, render / expected - 1 (R G B): exact at blood 0.03 / eval m0001 | translucent at 0.03 / eval m0001" \
	"| translucent at 0.06 / exact at 0.06 | (translucent at 0.06 / eval of the single bake at 0.06, not tested:" \
	"the family's interpolation between members): $nums"
set -- $flags
check "exact set: the blood 0.03 region within 0.5 % of eval of m0001" test "$1" = 1
# Within 1 % on 4.x too since the node's far field is the table's at the walk's albedo measured
# densely in the colour (blender_sss_albedo.h); with the profile table's G(0) (15 colours, 256
# samples on 4.x, 1 % high) this needed 2 %.  Seventh session, 128 samples: 4.5.15 -0.26 -0.06
# +0.06 % (0.03) and -0.06 +0.20 +0.15 % (0.06); 5.0.1 +0.15 +0.07 -0.18 % and +0.19 -0.15 -0.14 %.
check "translucent, blood 0.03 region within 1 % of eval of m0001" test "$2" = 1
check "translucent, blood 0.06 region within 1 % of the exact render" test "$3" = 1

# 3. Bad input: a family set whose entry for this Blender has no per-texel maps.
cp -r "$set" "$tmpd/bad"
python3 -c 'import json,sys; p=sys.argv[1]; m=json.load(open(p))
for v in m["translucent"]["versions"]: del v["maps"]
json.dump(m, open(p, "w"))' "$tmpd/bad/manifest.json"
B --python "$imp" -- "$tmpd/bad" --mode exact --scene box --samples 1 --render "$tmpd/bad.exr" >"$tmpd/bad.log" 2>&1
check "a family set without per-texel maps: the importer fails" test $? -ne 0 -a ! -s "$tmpd/bad.exr"
check "  ... naming translucent.versions[$blver].maps" grep -q "translucent.versions\[$blver\].maps" "$tmpd/bad.log"
tap_done
