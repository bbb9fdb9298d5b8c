#!/bin/sh
# skinbake export mitsuba: refusals (a POV-Ray-only shape, an open mesh for the
# volumetric layers, exit 2 and no output), the directory it writes, and a
# tiny MakeHuman head (40 x 30 px) rendered by skinbake_mitsuba in every mode:
#  - volumetric, two seeds with each estimator: the exit estimator's head mean
#    (exitnee.py) agrees with Mitsuba's volpath within 3 standard errors (the
#    error from each pixel's seed-to-seed difference), its variance gain and the
#    reference's own noise (CIEDE2000 between the seeds) are reported;
#  - the table, and the volumetric mean within a factor 2 of it (a sanity
#    check: the bridge's error is measured by scripts/validate-mitsuba.sh);
#  - translucent (fit with few photons): within 0.8-1.25 of the table's mean.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/mitsuba_env.sh"
MODEL=/usr/share/assimp/models/Collada/human.zae

"$SKINBAKE" bake --preset paper --solver ad --quiet --out "$tmpd/bake" >/dev/null 2>&1 || fail "bake paper"

# ---- refusals -------------------------------------------------------------------
cat >"$tmpd/hand.scene" <<'SC'
[camera]
type = perspective
location = 0 0 -3
angle = 40
[light key]
type = point
position = 2 1.5 -2.5
[skin skin]
preset = paper
[object h]
shape = hand
SC
"$SKINBAKE" export mitsuba --scene "$tmpd/hand.scene" --bake "$tmpd/bake" --out "$tmpd/o1" 2>"$tmpd/e1"
rc=$?
if [ $rc -eq 2 ] && [ ! -e "$tmpd/o1" ] && grep -q "object 'h': shape = hand is a POV-Ray macro" "$tmpd/e1"; then
	ok "shape = hand refused: exit 2, no output, names the object and the feature"
else
	fail "shape = hand: rc $rc, $(cat "$tmpd/e1")"
fi
if [ -f "$MODEL" ]; then
	# the eyes mesh is open (holes at the pupils): no interior for the layers
	sed -e 's/human-baseMesh/human-highpolyeyesMesh/' "$top_srcdir/tests/data/mitsuba/tiny-head.scene" >"$tmpd/eyes.scene"
	"$SKINBAKE" export mitsuba --scene "$tmpd/eyes.scene" --bake "$tmpd/bake" --mode volumetric --out "$tmpd/o2" 2>"$tmpd/e2"
	rc=$?
	if [ $rc -eq 2 ] && [ ! -e "$tmpd/o2" ] && grep -q "object 'head': the mesh .* has [0-9]* open edges, so it has no interior" "$tmpd/e2"; then
		ok "open mesh in volumetric mode refused: $(sed 's/^skinbake export mitsuba: //' "$tmpd/e2" | cut -c1-100)..."
	else
		fail "open mesh, volumetric: rc $rc, $(cat "$tmpd/e2")"
	fi
	"$SKINBAKE" export mitsuba --scene "$tmpd/eyes.scene" --bake "$tmpd/bake" \
		--mode translucent --out "$tmpd/o2t" 2>"$tmpd/e2t"
	rc=$?
	if [ $rc -eq 2 ] && [ ! -e "$tmpd/o2t" ] &&
		grep -q "open edges, so it has no interior" "$tmpd/e2t"; then
		ok "open mesh in translucent mode refused (exit 2, no output)"
	else
		fail "open mesh, translucent: rc $rc, $(cat "$tmpd/e2t")"
	fi
	if "$SKINBAKE" export mitsuba --scene "$tmpd/eyes.scene" --bake "$tmpd/bake" --mode table --out "$tmpd/o3" 2>"$tmpd/e3"; then
		ok "the same open mesh in table mode is exported"
	else
		fail "open mesh, table mode: $(cat "$tmpd/e3")"
	fi
else
	skip "open-mesh refusal: $MODEL missing (assimp-testmodels)"
	skip "open-mesh refusal, translucent: $MODEL missing"
	skip "open mesh in table mode: $MODEL missing"
fi
"$SKINBAKE" export mitsuba --scene "$top_srcdir/tests/data/pov/point.scene" --out "$tmpd/o4" 2>"$tmpd/e4"
rc=$?
if [ $rc -eq 2 ] && grep -q "names no bake and --bake is not given" "$tmpd/e4"; then
	ok "a skin without a bake: exit 2"
else
	fail "skin without bake: rc $rc $(cat "$tmpd/e4")"
fi

# ---- the export and the renders --------------------------------------------------
if [ ! -f "$MODEL" ]; then
	skip "tiny head: $MODEL missing (assimp-testmodels)"
	tap_done
	exit $?
fi
if "$SKINBAKE" export mitsuba --scene "$top_srcdir/tests/data/mitsuba/tiny-head.scene" --bake "$tmpd/bake" \
	--out "$tmpd/head" 2>"$tmpd/e5" && [ -s "$tmpd/head/head.ply" ] && [ -s "$tmpd/head/scene.json" ] &&
	grep -q '"open_edges":0' "$tmpd/head/manifest.json"; then
	ok "tiny head exported (manifest.json, scene.json, head.ply; the mesh is closed)"
else
	fail "tiny head export: $(cat "$tmpd/e5")"
fi
if [ -z "$MTS_PY" ]; then
	skip "renders: mitsuba is not importable (make the project venv: scripts/setup.sh, or set MITSUBA_PYTHON)"
	tap_done
	exit $?
fi
# the table; the volumetric layers with each estimator (2 seeds each: the noise
# of a head mean from the pixels' seed-to-seed differences); the translucent mode
render() { # NAME ARGS...: one render, its time line as a TAP line
	name=$1
	shift
	if nice "$MTS_PY" -m skinbake_mitsuba render "$tmpd/head" "$@" --out "$tmpd/$name.exr" \
		2>"$tmpd/$name.err"; then
		ok "$name: $(tail -1 "$tmpd/$name.err" | sed 's/^skinbake_mitsuba render: //')"
	else
		fail "render $name: $(tail -3 "$tmpd/$name.err")"
	fi
}
render table --mode table --spp 64
for e in exit volpath; do
	for seed in 1 2; do
		render "vol-$e-$seed" --mode volumetric --estimator $e --seed $seed --spp 32
	done
done
if nice "$MTS_PY" -m skinbake_mitsuba fit --bake "$tmpd/bake" --out "$tmpd/fit" \
	--skinbake "$SKINBAKE" --photons 20000 2>"$tmpd/fit.err"; then
	render translucent --mode translucent --fit "$tmpd/fit" --spp 32
else
	fail "fit: $(tail -3 "$tmpd/fit.err")"
fi
"$MTS_PY" -m skinbake_mitsuba render "$tmpd/head" --mode glass --out "$tmpd/x.exr" 2>"$tmpd/bad.err"
rc=$?
if [ $rc -eq 2 ] && [ ! -e "$tmpd/x.exr" ] &&
	grep -q "mode glass is not table, volumetric or translucent" "$tmpd/bad.err"; then
	ok "render --mode glass: exit 2"
else
	fail "render --mode glass: rc $rc $(cat "$tmpd/bad.err")"
fi
"$MTS_PY" - "$tmpd" >"$tmpd/cmp.txt" <<'PYEOF'
import sys
import numpy as np
import mitsuba as mi
mi.set_variant("scalar_rgb")
d = sys.argv[1]
def img(name):
    return np.array(mi.Bitmap(d + "/" + name + ".exr"), dtype=float)[..., :3]
t = img("table")
vol = {e: [img("vol-%s-%d" % (e, k)) for k in (1, 2)] for e in ("exit", "volpath")}
tr = img("translucent")
skin = t.sum(axis=2) > 0.02
good = all(np.isfinite(a).all() for a in [t, tr] + vol["exit"] + vol["volpath"])
print("%s|all images finite, %dx%d" % ("ok" if good else "fail", t.shape[1], t.shape[0]))
print("%s|the head covers %.0f %% of the table image"
      % ("ok" if 0.2 < skin.mean() < 0.95 else "fail", 100 * skin.mean()))
# the head's mean per channel and its standard error: a pixel's variance from its two
# seeds, (a - b)^2 / 2, summed over the head for one render's mean, halved for two
mean, err = {}, {}
for e, (a, b) in vol.items():
    mean[e] = 0.5 * (a[skin] + b[skin]).mean(axis=0)
    err[e] = np.sqrt((((a[skin] - b[skin]) ** 2) / 2).sum(axis=0) / 2) / skin.sum()
z = (mean["exit"] - mean["volpath"]) / np.sqrt(err["exit"] ** 2 + err["volpath"] ** 2)
print("%s|volumetric head mean, exit estimator %s +- %s, Mitsuba's volpath %s +- %s: z %s "
      "(within 3)" % ("ok" if np.all(np.abs(z) <= 3) else "fail", np.round(mean["exit"], 5),
                      np.round(err["exit"], 5), np.round(mean["volpath"], 5),
                      np.round(err["volpath"], 5), np.round(z, 2)))
gain = (err["volpath"] / err["exit"]) ** 2
print("ok|exit estimator: variance of the head mean %s times lower than volpath's at the same "
      "samples" % np.round(gain, 1))
# the volumetric reference's own noise between its two seeds (CIEDE2000 over the head)
from skinbake_mitsuba import colour
a, b = vol["exit"]
white = np.percentile(0.5 * (a + b)[skin][:, 1], 99)
de = colour.ciede2000(colour.lab(a, white), colour.lab(b, white))[skin]
print("ok|volumetric (exit, 32 spp per channel): seed 1 vs 2, median dE00 %.1f, "
      "95th percentile %.1f"
      % (np.median(de), np.percentile(de, 95)))
mt, mv, mr = t[skin].mean(axis=0), mean["exit"], tr[skin].mean(axis=0)
r = mv / mt
print("%s|mean colour over the head: table %s, volumetric %s (ratio %s; sanity: within a factor 2)"
      % ("ok" if np.all((r > 0.5) & (r < 2.0)) else "fail", np.round(mt, 4), np.round(mv, 4), np.round(r, 3)))
# translucent: the table's BRDF on flat ground, so its head mean stays near the table's;
# the clipped remainder at grazing angles adds light at the silhouette (docs/mitsuba.md)
q = mr / mt
print("%s|translucent mode: mean colour %s, %s of the table's (within 0.8-1.25)"
      % ("ok" if np.all((q > 0.8) & (q < 1.25)) else "fail", np.round(mr, 4), np.round(q, 3)))
PYEOF
while IFS='|' read -r verdict text; do
	if [ "$verdict" = ok ]; then ok "$text"; else fail "$text"; fi
done <"$tmpd/cmp.txt"
tap_done
