#!/usr/bin/env python3
"""Issue 21, round 5: candidate surface models around a CUReT fit, each
fitted on the 20 training points only and judged on the 181 held out.

Starts from a fitted preset file (adding-doubling, tests/brdf_model at all
205 CUReT points, --nodes 32 as scripts/fit-curet.py) and measures:

  ms        the preset as it is evaluated now: with multiple scattering on the
            facets, the lobe of the facets' later reflections
            (engine/microfacet_ms.h) added to the GGX lobe;
  no-ms     the same without that lobe (--no-ms-lobe: the lobe reflects
            less than the transport's Rsp, what eval gave before);
  beckmann  the analytic lobe with Beckmann facets instead of GGX (Walter et
            al. 2007 eqs. 25-27, separable Smith G; the transport stays GGX:
            the adding-doubling has no Beckmann walk), its m fitted on the
            training points (1-D);
  lobes2    two GGX lobes w D(a1) + (1 - w) D(a2) (as d'Eon & Luebke 2007
            use two specular lobes for skin), w, a1, a2 fitted on the
            training points, the subsurface part unchanged;
  patches   a surface of two film roughnesses side by side (table and lobe
            of each), w f(a1) + (1 - w) f(a2) over a grid of film alphas,
            w and the pair fitted on the training points.

Everything but the named freedom is the preset's.  The lobe-only variants
(beckmann, lobes2) are computed here from the same formulas as
engine/specular.c with the film's Fresnel (n = the preset's sebum index)
in place of the clear stack's (within 1 % of brdf_model's lobe at the 205
points).  Output: a TSV row per candidate (name, freedoms, training RMS,
held out RMS, back-side fall, forward rise, RMS against the Marschner 1999
fit over the 201 unsaturated points, description).

  curet-candidates.py --preset-file INI [--brdf-model PATH] [--curet TSV]
      [--marschner TSV] [--out DIR]
"""
import argparse
import math
import os
import subprocess
import sys

SAT = (202, 203, 204, 205)
TRAIN = (11.25, 33.75)


def read_curet(path):
    rows = []
    for line in open(path):
        if line.startswith("#") or line.startswith("idx"):
            continue
        c = line.split("\t")
        d = (float(c[2]) - float(c[4])) % 360.0
        d = 360.0 - d if d > 180.0 else d
        rows.append((int(c[0]), float(c[3]), float(c[1]), d, float(c[6])))
    return rows


def read_laf(path):
    ch = []
    for line in open(path):
        if line.startswith("#") or line.startswith("channel"):
            continue
        ch.append([float(v) for v in line.split("\t")[1:]])
    return ch


def laf(ch, ti, tv, dp):
    """Marschner 1999 Lafortune fit, mean of R, G, B (as validate-brdf.sh)."""
    r = math.pi / 180
    ux, uz = math.sin(ti * r), math.cos(ti * r)
    vx, vz = math.sin(tv * r) * math.cos(dp * r), math.cos(tv * r)
    tot = 0.0
    for c in ch:
        f = c[0] / math.pi
        for k in range(3):
            b = c[1 + 3 * k] * ux * vx + c[2 + 3 * k] * uz * vz
            if b > 0:
                f += b ** c[3 + 3 * k]
        tot += f
    return tot / 3


def brdf_model(exe, ini, pts, extra=()):
    with open(pts) as f:
        out = subprocess.run([exe, "--preset-file", ini, "--nodes", "32"] + list(extra), stdin=f,
                             check=True, capture_output=True, text=True).stdout
    return [[float(v) for v in line.split("\t")[:3]] for line in out.split("\n") if line]


def fresnel(c, n):
    s2 = 1 - (1 - c * c) / (n * n)
    if s2 <= 0:
        return 1.0
    s = math.sqrt(s2)
    rs = ((c - n * s) / (c + n * s)) ** 2
    rp = ((n * c - s) / (n * c + s)) ** 2
    return (rs + rp) / 2


def lobe(dist, a, ti, tv, dp, n):
    """Walter 2007 reflection lobe with the separable Smith G."""
    r = math.pi / 180
    L = (math.sin(ti * r), 0.0, math.cos(ti * r))
    V = (math.sin(tv * r) * math.cos(dp * r), math.sin(tv * r) * math.sin(dp * r), math.cos(tv * r))
    h = [L[k] + V[k] for k in range(3)]
    ln = math.sqrt(sum(x * x for x in h))
    if ln == 0:
        return 0.0
    ch = h[2] / ln
    cd = sum(L[k] * h[k] for k in range(3)) / ln
    if ch <= 0:
        return 0.0
    t2 = (1 - ch * ch) / (ch * ch)
    if dist == "ggx":
        D = a * a / (math.pi * (ch * ch * (a * a - 1) + 1) ** 2)
    else:
        D = math.exp(-t2 / (a * a)) / (math.pi * a * a * ch ** 4)

    def lam(mu):
        mu = min(max(mu, 1e-9), 1 - 1e-12)
        tt = math.sqrt(1 - mu * mu) / mu
        if dist == "ggx":
            return (-1 + math.sqrt(1 + a * a * tt * tt)) / 2
        x = 1 / (a * tt)
        return (math.erf(x) - 1) / 2 + math.exp(-x * x) / (2 * x * math.sqrt(math.pi))
    G = 1 / ((1 + lam(L[2])) * (1 + lam(V[2])))
    return fresnel(cd, n) * D * G / (4 * L[2] * V[2])


def golden(f, lo, hi, tol=1e-3):
    g = (math.sqrt(5) - 1) / 2
    a, b = lo, hi
    c1, c2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = f(c1), f(c2)
    while b - a > tol:
        if f1 < f2:
            b, c2, f2 = c2, c1, f1
            c1 = b - g * (b - a)
            f1 = f(c1)
        else:
            a, c1, f1 = c1, c2, f2
            c2 = a + g * (b - a)
            f2 = f(c2)
    return (a + b) / 2


def ini_value(path, section, key):
    sec = None
    for line in open(path):
        s = line.split(";")[0].strip()
        if s.startswith("["):
            sec = s.strip("[]")
        elif "=" in s and sec == section and s.split("=")[0].strip() == key:
            return s.split("=", 1)[1].strip()
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--preset-file", required=True)
    ap.add_argument("--brdf-model", default="./tests/brdf_model")
    ap.add_argument("--curet", default="/work/shared/skin_data/curet_sample39_brdf_205.tsv")
    ap.add_argument("--marschner", default=None)
    ap.add_argument("--out", default="curet-candidates-work")
    ap.add_argument("--alphas", default="0.2,0.3,0.55,0.7,0.9",
                    help="film alphas of the patches grid (besides the preset's)")
    a = ap.parse_args()
    if a.marschner is None:
        a.marschner = os.path.join(os.path.dirname(a.curet), "marschner1999_lafortune_skin_pbrtv1.tsv")
    os.makedirs(a.out, exist_ok=True)
    rows = read_curet(a.curet)
    ch = read_laf(a.marschner)
    pts = os.path.join(a.out, "points.txt")
    with open(pts, "w") as f:
        for r in rows:
            f.write("%g %g %g\n" % (r[1], r[2], r[3]))
    y = [r[4] for r in rows]
    m = [laf(ch, r[1], r[2], r[3]) for r in rows]
    tr = [i for i, r in enumerate(rows) if r[1] in TRAIN]
    he = [i for i, r in enumerate(rows) if r[1] not in TRAIN and r[0] not in SAT]
    ns = [i for i, r in enumerate(rows) if r[0] not in SAT]

    def rms(f, sel, ref=y):
        return 100 * math.sqrt(sum(((f[i] - ref[i]) / ref[i]) ** 2 for i in sel) / len(sel))

    def at(f, ti, tv, dp):
        for i, r in enumerate(rows):
            if abs(r[1] - ti) < .01 and abs(r[2] - tv) < .01 and abs(r[3] - dp) < .01:
                return f[i]

    def row(name, free, f, desc):
        fall = at(f, 11.25, 78.75, 0) / at(f, 11.25, 33.75, 0)
        rise = at(f, 33.75, 78.75, 180) / at(f, 33.75, 33.75, 180)
        print("%s\t%s\t%.1f\t%.1f\t%.2f\t%.2f\t%.1f\t%s" % (name, free, rms(f, tr), rms(f, he), fall, rise,
                                                      rms(f, ns, m), desc), flush=True)

    base = brdf_model(a.brdf_model, a.preset_file, pts)
    nolobe = brdf_model(a.brdf_model, a.preset_file, pts, ["--no-ms-lobe"])
    alpha = float(ini_value(a.preset_file, "surface", "roughness"))
    n_film = float(ini_value(a.preset_file, "sebum", "n") or 1.5)
    tot = [v[0] for v in base]
    dif = [v[1] for v in base]
    print("candidate\tfreedoms\ttrain\theld\tfall\trise\tmarschner\tdescription")
    row("ms", 0, tot, "as fitted, with the lobe of the facets' later reflections")
    row("no-ms", 0, [v[0] for v in nolobe], "as fitted, without that lobe")
    ms_only = [base[i][2] - nolobe[i][2] for i in range(len(rows))]   # the ms lobe itself

    def with_lobe(fl):
        return [dif[i] + ms_only[i] + fl[i] for i in range(len(rows))]
    cache = {}

    def lobes(dist, al):
        k = (dist, round(al, 6))
        if k not in cache:
            cache[k] = [lobe(dist, al, r[1], r[2], r[3], n_film) for r in rows]
        return cache[k]
    ab = golden(lambda al: rms(with_lobe(lobes("beckmann", al)), tr), 0.05, 1.0)
    row("beckmann", 1, with_lobe(lobes("beckmann", ab)), "Beckmann lobe, m %.3f fitted (transport GGX)" % ab)
    best = None
    for a1 in (0.15, 0.25, 0.35, 0.45):
        for a2 in (0.5, 0.65, 0.8, 1.0):
            l1, l2 = lobes("ggx", a1), lobes("ggx", a2)
            for k in range(21):
                w = k / 20
                j = rms(with_lobe([w * l1[i] + (1 - w) * l2[i] for i in range(len(rows))]), tr)
                if best is None or j < best[0]:
                    best = (j, a1, a2, w)
    _, a1, a2, w = best
    l1, l2 = lobes("ggx", a1), lobes("ggx", a2)
    row("lobes2", 3, with_lobe([w * l1[i] + (1 - w) * l2[i] for i in range(len(rows))]),
        "two GGX lobes %.2f x alpha %.2f + %.2f x alpha %.2f" % (w, a1, 1 - w, a2))
    grid = {alpha: tot}
    for s in a.alphas.split(","):
        al = float(s)
        ini = os.path.join(a.out, "film%s.ini" % s)
        with open(ini, "w") as f:
            for line in open(a.preset_file):
                k = line.split("=")[0].strip()
                f.write("%s = %s\n" % (k, s) if k in ("roughness", "roughness_skin", "roughness_sebum") else line)
        grid[al] = [v[0] for v in brdf_model(a.brdf_model, ini, pts)]
    best = None
    keys = sorted(grid)
    for i1 in range(len(keys)):
        for i2 in range(i1 + 1, len(keys)):
            f1, f2 = grid[keys[i1]], grid[keys[i2]]
            for k in range(41):
                w = k / 40
                j = rms([w * f1[i] + (1 - w) * f2[i] for i in range(len(rows))], tr)
                if best is None or j < best[0]:
                    best = (j, keys[i1], keys[i2], w)
    _, a1, a2, w = best
    row("patches", 3, [w * grid[a1][i] + (1 - w) * grid[a2][i] for i in range(len(rows))],
        "film alpha %.3g on %.0f %% of the surface, %.3g on the rest" % (a1, 100 * w, a2))


if __name__ == "__main__":
    sys.exit(main())
