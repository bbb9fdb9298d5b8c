#!/bin/sh
# The baked table as a Mitsuba 3 BSDF (skinbake_mitsuba's skinbake_table) against
# skinbake eval, pixel by pixel: a unit sphere under a directional light, seen
# orthographically, rendered at each of paper's wavelengths in llvm_ad_spectral
# (1 nm film band) and once in llvm_ad_rgb; each checked pixel within 1 % of the
# pixel mean (3 x 3 points) of eval's f cos(theta_i).
# Then the plugin's resampled table (tablegrid.py) against eval point by point.
. "$top_srcdir/tests/tap.sh"
. "$top_srcdir/tests/mitsuba_env.sh"
[ -n "$MTS_PY" ] || mts_skip_all

"$SKINBAKE" bake --preset paper --solver ad --quiet --out "$tmpd/bake" >/dev/null 2>&1 || { fail "bake paper"; tap_done; exit 1; }

# ---- bad input ------------------------------------------------------------------
"$MTS_PY" -m skinbake_mitsuba sphere --bake "$tmpd" --out "$tmpd/x.npy" >"$tmpd/bad.out" 2>"$tmpd/bad.err"
rc=$?
if [ $rc -eq 2 ] && [ ! -e "$tmpd/x.npy" ] && grep -q "no manifest.json" "$tmpd/bad.err"; then
	ok "sphere --bake of a directory without a bake: exit 2, no output"
else
	fail "sphere --bake without manifest: rc $rc $(cat "$tmpd/bad.err")"
fi
"$MTS_PY" -m skinbake_mitsuba sphere --bake "$tmpd/bake" --wavelength 900 --out "$tmpd/x.npy" 2>"$tmpd/bad.err"
rc=$?
if [ $rc -eq 2 ] && [ ! -e "$tmpd/x.npy" ] && grep -q "wavelength 900 is outside \[360, 830\] nm" "$tmpd/bad.err"; then
	ok "sphere --wavelength 900: exit 2 naming the value and range"
else
	fail "sphere --wavelength 900: rc $rc $(cat "$tmpd/bad.err")"
fi

# ---- renders ---------------------------------------------------------------------
N=32
for w in 470 550 656 rgb; do
	opt="--wavelength $w"
	[ $w = rgb ] && opt=
	if nice "$MTS_PY" -m skinbake_mitsuba sphere --bake "$tmpd/bake" $opt --size $N --spp 256 \
		--out "$tmpd/s$w.npy" 2>"$tmpd/s$w.err"; then
		ok "$(tail -1 "$tmpd/s$w.err")"
	else
		fail "sphere $w: $(tail -3 "$tmpd/s$w.err")"
	fi
done

"$MTS_PY" - "$tmpd" "$SKINBAKE" "$N" "$top_srcdir/tests/lib" >"$tmpd/cmp.txt" <<'PYEOF'
import json, math, subprocess, sys
import numpy as np
d, skinbake, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
sys.path.insert(0, sys.argv[4])
import ortho_sphere as osp          # the BRDF angles at a point of the sphere
light = np.array([0.5, 0.3, 0.8])
light /= np.linalg.norm(light)
view = np.array([0.0, 0.0, 1.0])

def ev(x, y):
    """eval's f cos(theta_i) at the sphere point over (x, y): per wavelength and rgb."""
    nrm = np.array([x, y, math.sqrt(max(0.0, 1.0 - x * x - y * y))])
    ti, to, ph = (float(a) for a in osp.angles(nrm, light, view))
    out = subprocess.run([skinbake, "eval", "--bake", d + "/bake", "--theta-in", repr(ti),
                          "--theta-out", repr(to), "--phi", repr(ph), "--json"],
                         capture_output=True, text=True, check=True).stdout
    j = json.loads(out)
    return np.array(j["total"] + j["rgb_total"]) * (nrm @ light), j["wavelengths_nm"]

imgs = {w: np.load("%s/s%s.npy" % (d, w)) for w in ("470", "550", "656", "rgb")}
worst = {}
count = 0
for r in range(2, n, 5):
    for c in range(2, n, 5):
        x = (c + 0.5) / n * 2 - 1
        y = 1 - (r + 0.5) / n * 2
        nz2 = 1.0 - x * x - y * y
        # whole pixel on the lit sphere, away from the silhouette and the terminator
        if nz2 < 0.09 or (np.array([x, y, math.sqrt(nz2)]) @ light) < 0.15:
            continue
        acc = 0.0
        for dy in (-1 / 3, 0.0, 1 / 3):
            for dx in (-1 / 3, 0.0, 1 / 3):
                v, wl = ev(x + dx * 2 / n, y - dy * 2 / n)
                acc = acc + v / 9.0
        count += 1
        got = [imgs["470"][r, c, 0], imgs["550"][r, c, 0], imgs["656"][r, c, 0]] + list(imgs["rgb"][r, c, :3])
        names = ["470 nm", "550 nm", "656 nm", "R", "G", "B"]
        for k, name in enumerate(names):
            e = got[k] / acc[k] - 1.0
            if name not in worst or abs(e) > abs(worst[name][0]):
                worst[name] = (e, r, c)
for name in ("470 nm", "550 nm", "656 nm", "R", "G", "B"):
    e, r, c = worst[name]
    print("%s|%s: worst of %d pixels %+.3f %% (pixel %d,%d) against eval's pixel mean; tolerance 1 %%"
          % ("ok" if abs(e) <= 0.01 else "fail", name, count, 100 * e, r, c))
PYEOF
[ -s "$tmpd/cmp.txt" ] || fail "the comparison printed nothing"
while IFS='|' read -r verdict text; do
	if [ "$verdict" = ok ]; then ok "$text"; else fail "$text"; fi
done <"$tmpd/cmp.txt"
# ---- the plugin's resampled table against eval, point by point ---------------------
# tablegrid.py resamples eval's function on a grid uniform in u = acos(1 - 4 theta / pi)
# and delta_phi; trilinear lookup on it is within 1e-3 of eval below 85 deg (its stated
# error: h^2 f'' / 8 at the grid's spacing); at grazing the BRDF falls to 0 and only
# the absolute error (relative to the table's largest value) is bounded, by 1e-3.
"$MTS_PY" - "$tmpd/bake" "$SKINBAKE" "$top_srcdir/exporters/mitsuba" >"$tmpd/grid.txt" <<'PYEOF'
import json, math, subprocess, sys
import numpy as np
d, skinbake = sys.argv[1], sys.argv[2]
sys.path.insert(0, sys.argv[3])
import mitsuba as mi
mi.set_variant("scalar_rgb")
from skinbake_mitsuba import tablegrid as tg
man = json.load(open(d + "/manifest.json"))
bmp = mi.Bitmap(d + "/brdf.exr")
names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
arr = np.array(bmp, dtype=np.float32)
planes = np.stack([arr[:, :, i] for i, n in enumerate(names) if n.startswith("fr.")])
g = tg.resample(man, planes)
top = float(planes.max())

def lookup(gw, ti, to, ph):
    s = (tg.N_THETA - 1) / math.pi
    x = np.array([math.acos(1 - 4 * ti / math.pi) * s, math.acos(1 - 4 * to / math.pi) * s,
                  ph * (tg.N_PHI - 1) / math.pi])
    i = np.minimum(np.floor(x).astype(int), [tg.N_THETA - 2, tg.N_THETA - 2, tg.N_PHI - 2])
    t = x - i
    v = 0.0
    for da in (0, 1):
        for db in (0, 1):
            for dc in (0, 1):
                w = (t[0] if da else 1 - t[0]) * (t[1] if db else 1 - t[1]) * (t[2] if dc else 1 - t[2])
                v += w * gw[i[0] + da, i[1] + db, i[2] + dc]
    return v

rng = np.random.default_rng(26)
rel, ab = 0.0, 0.0
for s in range(40):
    a, b, c = rng.uniform(0, 90), rng.uniform(0, 90), rng.uniform(0, 180)
    out = subprocess.run([skinbake, "eval", "--bake", d, "--theta-in", repr(a), "--theta-out", repr(b),
                          "--phi", repr(c), "--json"], capture_output=True, text=True, check=True).stdout
    ev = json.loads(out)["diffuse"]
    for w in range(g.shape[0]):
        v = lookup(g[w], math.radians(a), math.radians(b), math.radians(c))
        if max(a, b) < 85:
            rel = max(rel, abs(v / ev[w] - 1))
        ab = max(ab, abs(v - ev[w]) / top)
print("%s|resampled table vs eval at 40 random angles: worst %.1e relative below 85 deg (tolerance 1e-3)"
      % ("ok" if rel <= 1e-3 else "fail", rel))
print("%s|resampled table vs eval: worst %.1e of the table's largest value at any angle (tolerance 1e-3)"
      % ("ok" if ab <= 1e-3 else "fail", ab))
PYEOF
[ -s "$tmpd/grid.txt" ] || fail "the grid comparison printed nothing"
while IFS='|' read -r verdict text; do
	if [ "$verdict" = ok ]; then ok "$text"; else fail "$text"; fi
done <"$tmpd/grid.txt"
tap_done
