#!/bin/sh
# export blender --mode translucent with the real Blender (issue 27 steps 3-4): Cycles' random
# walk fitted to the bake's Rd(r) beside the rest of the table (blender_sss.h, translucent.py).
# 1. Flat skin under one sun: the importer's closed box (200 x 200 x 50 mm, so the walk has an
#    inside and the centre is far from the edges), exact mode, sun at 45 deg, view at 30 deg,
#    delta phi 45 deg, 64 px at 256 samples, centre quarter: within 1 % of E cos(theta_i) f from
#    `skinbake eval` per channel (the node is about 94 % of the red signal, so this checks the
#    split: the rest = table - the node's far field G(0) / pi).
# 2. A slab 1, 2 and 4 mm thick lit from behind (scripts/sss_profile.py cycles --back --entry:
#    the importer's nodes, weighted by the local thickness where this Blender has a
#    transmission table, blender_sss_thick.h): the transmitted exitance against `skinbake
#    simulate` Tt of the same stack cut to that thickness (light entering the deepest layer),
#    within 20 % per channel above 1e-4.  A channel whose walk passes less than 0.8 Tt at full
#    weight, and a Blender without a table (the walk unweighted transmits up to twice the
#    layered slab's, docs/translucency.md), are TAP TODO.
# 3. Bad input: a translucent section with a radius of 0, or without a fit for this Blender
#    (major.minor), is refused by the importer; a bake without a radial profile by the export.
# Runs on the Blender $BLENDER names (Debian's 3.4, or a bpy venv through tests/bpy-blender:
# tests/blender_matrix.sh runs it on 4.5 and 5.0), with that version's fit from the set.
# Paper bake (adding-doubling, Monte Carlo Rd(r)); about 7 minutes per version at load 12-16.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/lib/blender.sh"
. "$top_srcdir/tests/lib/translucent_fit.sh"
imp="$top_srcdir/exporters/blender/import_skin.py"
PROF="$top_srcdir/scripts/sss_profile.py"
if [ -z "$BLENDER" ] || ! command -v "$BLENDER" >/dev/null 2>&1 || ! command -v python3 >/dev/null 2>&1; then
	fail "blender or python3 is missing (BLENDER='$BLENDER'): the project's set-up installs them"
	tap_done
	exit 1
fi
# Known limits are todo lines (tests/tap.sh).
blver=$(B --python-expr 'import bpy; print("BLVER %d.%d" % tuple(bpy.app.version[:2]))' \
	2>/dev/null | sed -n 's/^BLVER //p' | head -n 1)
echo "# Blender $blver ($BLENDER)"
bake="$tmpd/paper"
"$SKINBAKE" bake --preset paper --out "$bake" --quiet >"$tmpd/bake.log" 2>&1
check "bake paper" test $? -eq 0
set="$tmpd/set"
"$SKINBAKE" export blender --bake "$bake" --out "$set" --mode translucent >"$tmpd/export.log" 2>&1
check "export blender --mode translucent" test $? -eq 0 -a -f "$set/manifest.json"
check "  ... the manifest has the fitted node" python3 -c 'import json,sys
sys.exit(json.load(open(sys.argv[1]))["translucent"]["node"] != "ShaderNodeSubsurfaceScattering")' "$set/manifest.json"

# A Blender without its own fit in the set imports it with the fallback, the node's far field as a
# diffuse (tests/lib/translucent_fit.sh); section 2 and the radius-0 check need this version's fit.
hasfit=1
translucent_fit "$set" "$blver" "back light and the radius-0 check" || hasfit=0

# 1. Flat skin, exact mode with the node (with this version's fit) or with the fallback's diffuse.
B --python "$imp" -- "$set" --mode exact --scene box --samples 256 --render "$tmpd/box.exr" >"$tmpd/box.log" 2>&1
check "exact mode with the translucent set: import and render" test $? -eq 0
if [ "$hasfit" = 1 ]; then
	check "  ... the importer added this Blender's fitted node" \
		grep -q "translucent: Cycles $blver" "$tmpd/box.log"
else
	check "  ... no fit for this Blender: the far field as a diffuse, said" \
		grep -q "translucent: no fit for this Blender" "$tmpd/box.log"
fi
r=$(python3 - "$SKINBAKE" "$bake" "$set/manifest.json" "$tmpd/box.log" <<'PY'
import json, math, subprocess, sys
skinbake, bake, man, log = sys.argv[1:5]
e = json.load(open(man))["exact"]
ref = e["reference"]
ti = math.degrees(math.acos(ref["cos_light"]))
to = math.degrees(math.acos(ref["cos_view"]))
out = subprocess.run([skinbake, "eval", "--bake", bake, "--theta-in", "%.6f" % ti, "--theta-out", "%.6f" % to,
                      "--phi", "%.6f" % ref["delta_phi_deg"], "--json"], capture_output=True, text=True, check=True).stdout
f = json.loads(out)["rgb_total"]
want = [e["sun_strength_w_m2"] * ref["cos_light"] * x for x in f]
got = None
for line in open(log):
    if line.startswith("SKINBAKE_CENTER "):
        got = [float(x) for x in line.split()[1:4]]
err = [g / w - 1 for g, w in zip(got, want)]
print(" ".join("%+.4f" % x for x in err), int(max(abs(x) for x in err) <= 0.01))
PY
)
errs=$(echo "$r" | cut -d' ' -f1-3)
echo "# flat box, translucent set in exact mode: render / eval - 1 per R, G, B: $errs"
# The node's far field is the table's at the walk's albedo measured densely in the colour
# (blender_sss_albedo.h): with the profile table's G(0), linear between 15 colours (and 3.4.1's
# rendered at 64 samples, 0.6 % low), 3.4.1 blue (colour 0.029) read +1.23 % and 4.5 green
# (0.046) -1.32 %; with it 3.4.1 +0.67, -0.01, +0.09 %, 4.5.15 +0.01, +0.30, +0.10 %, 5.0.1
# -0.13, -0.74, -0.47 % (256 samples).
check "flat skin within 1 % of eval per channel ($errs)" \
	test "$(echo "$r" | cut -d' ' -f4)" = 1

if [ "$hasfit" = 1 ]; then

# 2. Back light through slabs of 1, 2 and 4 mm (the node alone: the rest of the table is a
# surface BRDF and adds nothing behind).  With this version's transmission table the set's
# node is weighted by the local thickness (blender_sss_thick.h): scripts/sss_profile.py --entry
# renders the importer's own nodes (translucent.thickness_shader) from the manifest's entry.
python3 -c 'import json,sys; t=json.load(open(sys.argv[1]))["translucent"]
v = [v for v in t["versions"] if v["blender"] == sys.argv[2]][0]
json.dump(v, open(sys.argv[3], "w"))' "$set/manifest.json" "$blver" "$tmpd/entry.json"
args=$(python3 -c 'import json,sys; v=json.load(open(sys.argv[1]))
print("--colour " + ",".join("%.6g" % x for x in v["colour"]) + " --radius "
      + ",".join("%.6g" % (x * 1e3) for x in v["radius_m"])
      + " --method " + v["falloff"].lower() + (" --entry " + sys.argv[1] if "thickness" in v else ""))' \
	"$tmpd/entry.json")
case $args in *--entry*) thick=1 ;; *) thick=0 ;; esac
echo "# back light: $([ $thick = 1 ] && echo "node weighted by the thickness (this Blender's transmission table)" || echo "no transmission table for Blender $blver: the node unweighted")"
for thk in 1 2 4; do  # not d: check() sets d
	# 256 samples: at 64 the blue node (a tenth of the red one's weight, so rarely picked) came
	# out 0.80 of Tt at 1 mm where 256 give 0.85 and the weights predict 0.95.
	# shellcheck disable=SC2086
	BLENDER="$BLENDER" python3 "$PROF" cycles $args --edges 0 --back --depth $thk --samples 256 \
		--json "$tmpd/back$thk.json" 2>"$tmpd/back.log"
	r=$(python3 - "$SKINBAKE" "$bake" "$thk" "$tmpd/back$thk.json" "$tmpd/entry.json" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
from slab_tt import slab_tt_rgb
skinbake, bake, d_mm, prof, entry = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4], sys.argv[5]
m = json.load(open(bake + "/manifest.json"))
sim = slab_tt_rgb(skinbake, m, d_mm)
ren = json.load(open(prof))["g"][0]
ratio = [r / s if s > 1e-4 else 1.0 for r, s in zip(ren, sim)]
# A channel whose walk, at full weight, passes less than 0.8 of Tt (the weight only lowers
# the walk's transmission) is a known limit, not a failure of the weight.
th = json.load(open(entry)).get("thickness")
weak = [0, 0, 0]
if th:
    k = min(range(len(th["d_m"])), key=lambda i: abs(th["d_m"][i] * 1e3 - d_mm))
    weak = [int(th["t_walk"][k][c] < 0.8 * th["tt_stack"][k][c]) for c in range(3)]
ok = [abs(x - 1) <= 0.2 for x in ratio]
print(" ".join("%.4g/%.4g" % (r, s) for r, s in zip(ren, sim)),
      int(all(o or w for o, w in zip(ok, weak))), int(all(ok)),
      "".join("RGB"[c] for c in range(3) if weak[c] and sim[c] > 1e-4) or "-")
PY
)
	set -- $r
	echo "# back light $thk mm: rendered/simulated Tt per R, G, B (below 1e-4 not compared): $1 $2 $3"
	if [ $thick = 1 ]; then
		check "Cycles: back light through $thk mm within 20 % of simulated Tt (but for channels where the walk passes less than Tt at full weight: $6; $1 $2 $3)" \
			test "$4" = 1
		[ "$6" = - ] || todo "Cycles: back light through $thk mm within 20 % in channel $6 too ($1 $2 $3)" \
			"the fitted walk passes less than the layered slab there, and the weight can only lower it" \
			test "$5" = 1
	else
		todo "Cycles: back light through $thk mm within 20 % of simulated Tt ($1 $2 $3)" \
			"no transmission table for this Blender: a homogeneous walk fitted to the reflection transmits up to 2x the layered slab" \
			test "$5" = 1
	fi
done
fi

# 3. Bad input: the importer refuses a translucent section with a radius of 0.
if [ "$hasfit" = 1 ]; then
cp -r "$set" "$tmpd/bad"
python3 -c 'import json,sys; p=sys.argv[1]; m=json.load(open(p))
for v in m["translucent"]["versions"]: v["radius_m"][0] = 0
json.dump(m, open(p, "w"))' "$tmpd/bad/manifest.json"
B --python "$imp" -- "$tmpd/bad" --mode exact --scene box --samples 1 --render "$tmpd/bad.exr" >"$tmpd/bad.log" 2>&1
check "a translucent radius of 0: the importer fails" test $? -ne 0 -a ! -s "$tmpd/bad.exr"
check "  ... naming translucent.versions[$blver].radius_m" \
	grep -q "translucent.versions\[$blver\].radius_m" "$tmpd/bad.log"
fi
# ... and a set without a fit for this Blender (5.0.1 rendered the 3.4.1 fit 12 % dark): never
# another version's fit; the fallback, said (on a Blender without a fit, translucent_fit above).
if [ "$hasfit" = 1 ]; then
cp -r "$set" "$tmpd/bad2"
python3 -c 'import json,sys; p=sys.argv[1]; m=json.load(open(p))
t = m["translucent"]
t["versions"] = [v for v in t["versions"] if v["blender"] != sys.argv[2]]
json.dump(m, open(p, "w"))' "$tmpd/bad2/manifest.json" "$blver"
B --python "$imp" -- "$tmpd/bad2" --mode exact --scene box --samples 1 --render "$tmpd/bad2.exr" >"$tmpd/bad2.log" 2>&1
check "a set without a fit for this Blender: the importer renders the fallback" \
	test $? -eq 0 -a -s "$tmpd/bad2.exr"
check "  ... no subsurface node, saying so and naming the fits it has" \
	grep -q "translucent: no fit for this Blender .*(fits for .*): no subsurface node" "$tmpd/bad2.log"
fi
# 4. --mode auto, export blender's default: a bake with Rd(r) goes translucent, saying so; with
# --textures (the node carries no detail normal map) or a bake without Rd(r), exact saying why.
"$SKINBAKE" export blender --bake "$bake" --out "$tmpd/auto" --lut-cos 8 --lut-phi 3 2>"$tmpd/auto.log" >/dev/null
check "export blender (default --mode auto) on a bake with Rd(r): a translucent set" \
	test $? -eq 0 -a -n "$(grep -l '"translucent"' "$tmpd/auto/manifest.json" 2>/dev/null)"
check "  ... saying so" grep -q "translucent (--mode auto: a bake with Rd(r)" "$tmpd/auto.log"
"$SKINBAKE" texture --out "$tmpd/tex" --size 16 --quiet >/dev/null 2>&1
"$SKINBAKE" export blender --bake "$bake" --textures "$tmpd/tex" --out "$tmpd/autotex" --lut-cos 8 \
	--lut-phi 3 2>"$tmpd/autotex.log" >/dev/null
check "  ... with --textures: exact, saying why" sh -c "test -f '$tmpd/autotex/manifest.json' &&
	! grep -q '\"translucent\"' '$tmpd/autotex/manifest.json' &&
	grep -q 'exact (--mode auto: --textures' '$tmpd/autotex.log'"
# ... and a bake without a radial profile: export refuses it (exit 2, naming radial.rd_r, no set).
cp -r "$bake" "$tmpd/norad"
python3 -c 'import json,sys; p=sys.argv[1]; m=json.load(open(p)); del m["radial"]["rd_r"]
json.dump(m, open(p, "w"))' "$tmpd/norad/manifest.json"
"$SKINBAKE" export blender --bake "$tmpd/norad" --out "$tmpd/noradset" --mode translucent \
	>/dev/null 2>"$tmpd/norad.log"
check "a bake without a radial profile: export exits 2 and writes nothing" \
	test $? -eq 2 -a ! -e "$tmpd/noradset"
check "  ... naming radial.rd_r" grep -q "radial.rd_r" "$tmpd/norad.log"
"$SKINBAKE" export blender --bake "$tmpd/norad" --out "$tmpd/noradauto" --lut-cos 8 --lut-phi 3 \
	>/dev/null 2>"$tmpd/noradauto.log"
check "  ... under --mode auto: exact, naming radial.rd_r" sh -c "test -f '$tmpd/noradauto/manifest.json' &&
	! grep -q '\"translucent\"' '$tmpd/noradauto/manifest.json' &&
	grep -q 'exact (--mode auto: .*radial.rd_r' '$tmpd/noradauto.log'"
tap_done
