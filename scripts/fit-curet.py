#!/usr/bin/env python3
"""Fit the free physical parameters of a skin preset to CUReT sample 39.

Issue 16 item 3.  Free parameters: epidermal melanin fraction, dermal blood
fraction, a scale on the reduced scattering of epidermis and dermis, the sebum
film (on: 5 um, or off) and the GGX roughness of the top surface; everything
else is the physiological presets' model (docs/presets.md), with
`base = medium-oily` or `base = medium-dry` for the rest.  The fit uses only
the CUReT points at incidence 11.25 and 33.75 deg (20 of 205, in and out of
the plane of incidence); scripts/validate-brdf.sh reports the error on the
other points.

Model evaluation is one call, Model.model_brdf(params), with two solvers:
--solver mc (default) bakes the preset at the training incidence angles
(`skinbake bake`, Monte Carlo) and evaluates the bake with tests/brdf_points;
--solver ad evaluates it with tests/brdf_model, the adding-doubling solver
(src/engine/ad.h) at the points themselves, deterministic and without a bake.  CUReT's values are the
mean of a camera's R, G and B; the model's are the mean over 470, 550 and
656 nm (docs/presets.md, "Colour and RGB").

The sebum film is clear, so its thickness does not change a plane-parallel
model (only its two interfaces count): it is fitted as on or off.  Roughness
enters only the analytic specular lobe, so with Monte Carlo the best
roughness is found for each bake by a 1-D search over brdf_points --alpha
without baking again, and melanin, blood and the scattering scale are
searched by Nelder-Mead in their logarithms; with adding-doubling (no bake to
save) all four are in one Nelder-Mead.  Each is run once with and once
without sebum.

--rough-epi (issue 21, round 3) frees the roughness of the epidermis's top
under the film ([epidermis] top_roughness) from the film's top ([surface]
roughness): the paper's sebum smoothing a rough skin surface.  --solver ad
takes multiple scattering on the facets too (src/engine/ad_rough.h) and, with
--nodes 32 (default), solves once per evaluation at a fixed quadrature.
--evaluate INI prints a preset file's errors on the training and held-out
points, fall and rise (adding-doubling at all 205 points); --train all fits
every point but the 4 saturated ones (a diagnostic of the model's best).

--macro (issue 21, round 4) adds the RMS slope m of a mm-scale relief
([surface] macro_slope, src/engine/macro.h): the whole BRDF (table and
lobe) integrated over Beckmann-tilted facets with height-correlated Smith
shadowing; tests/brdf_model and the bakes' evaluation apply it, so it is one
more simplex parameter with either solver.

With --rough (issue 21) the roughness is also the GGX alpha of the top
boundary in the subsurface transport ([surface] roughness): light enters and
leaves the skin through the microfacets, so every roughness needs its own
bake and, with Monte Carlo, the roughness joins the simplex as with
adding-doubling.  --multiple makes the facets scatter light as often as it
meets them ([surface] multiple_scattering = 1).  --sebum on|off fits one of
the two films only.

With --multiple the lobe also carries the facets' later reflections
(issue 21, round 5: src/engine/microfacet_ms.h, added by tests/brdf_model
and by eval of a bake), so the fitted preset reflects what its transport's
rough top reflects.

--objective log (issue 21, round 7) minimises the mean of ln(f/y)^2 instead
of the squared relative error (which weighs a model too high by a factor more
than one too low by the same factor); --step-scale shrinks the simplex's first
steps to refine near --start.

Monte Carlo noise (with --solver ad the errors are the solver's estimates,
about 1e-4 relative, and the same formulas hold): the objective is the mean over the points of
r_i^2 - e_i^2, with r_i = (f_i - y_i) / y_i the relative error and e_i the
relative standard error of f_i (from the bake's batches); E[r_i^2] = true
r_i^2 + e_i^2, so the objective is an unbiased estimate of the squared RMS
relative error, which is what the goal (8 %) is stated in.  Every bake uses
the same seed (common random numbers), so differences between nearby
parameters are much less noisy than the values.  Its own standard deviation,
about 2/N sqrt(sum r_i^2 e_i^2), is printed with every evaluation; the simplex
stops when the spread of its objective values falls below 3 times that.

Usage (from a build directory, after `make tests/brdf_points`):
  python3 $top_srcdir/scripts/fit-curet.py [--target-error 0.02] [--out DIR]
Prints the log of every evaluation and, at the end, the preset's INI text.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

TRAIN_THETA_I = (11.25, 33.75)
SATURATED = (202, 203, 204, 205)  # grazing mirror points where CUReT saturates (validate-brdf.sh)
SEBUM_ON_CM = 0.0005            # the physiological presets' oily film (5 um)
BASE_EPI_MUSP500 = 69.0         # base presets' musp500 (docs/presets.md)
BASE_DERM_MUSP500 = 45.6
# Bounds: melanosome fraction up to Jacques 1998's darkest skin (43 %); dermal
# blood 0.2-7 % (Jacques 2013 Table 3, skin-optics.md A2.9; --blood-max 0.2,
# the preset key's limit, lifts it); the scattering scale within a factor 2 of
# the Salomatina 2006 means (our bound); GGX alpha as the preset keys.
# The epidermis top under the film (--rough-epi): the same range as alpha.
BOUNDS = {"melanin": (0.0005, 0.43), "blood": (0.002, 0.07), "scatter": (0.5, 2.0), "alpha": (0.02, 1.0),
          "alpha_epi": (0.02, 1.0), "macro": (0.005, 0.8)}
# The free parameters, in the simplex's order (main() appends alpha, alpha_epi, macro).
NAMES = ["melanin", "blood", "scatter"]


def read_curet(path):
    """CUReT rows as (idx, theta_i, theta_v, delta_phi [0 back, 180 mirror], brdf)."""
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("idx"):
                continue
            c = line.split("\t")
            idx, tv, pv, ti, pi_, brdf = int(c[0]), float(c[1]), float(c[2]), float(c[3]), float(c[4]), float(c[6])
            d = (pv - pi_) % 360.0
            if d > 180.0:
                d = 360.0 - d
            rows.append((idx, ti, tv, d, brdf))
    return rows


class Model:
    """The model: parameters -> BRDF at the training points, with errors."""

    def __init__(self, args, points):
        self.a = args
        self.points = points
        self.cache = {}
        self.n_bakes = 0
        self.seconds = 0.0
        os.makedirs(args.out, exist_ok=True)
        self.pts_file = os.path.join(args.out, "points.txt")
        with open(self.pts_file, "w") as f:
            for p in points:
                f.write("%g %g %g\n" % (p[1], p[2], p[3]))

    def preset_ini(self, q, alpha):
        base = "medium-oily" if q["sebum"] else "medium-dry"
        a_epi = q.get("alpha_epi", 0.0)
        return ("[skin]\nbase = %s\nname = curet39-fit\n"
                "[sebum]\nthickness = %g\n"
                "[epidermis]\nmelanin = %.6g\nmusp500 = %.6g\n%s"
                "[dermis]\nblood = %.6g\nmusp500 = %.6g\n"
                "[surface]\nroughness_skin = %.4g\nroughness_sebum = %.4g\n%s"
                % (base, SEBUM_ON_CM if q["sebum"] else 0, q["melanin"], BASE_EPI_MUSP500 * q["scatter"],
                   ("top_roughness = %.4g\n" % a_epi if a_epi > 0 and q["sebum"] else ""),
                   q["blood"], BASE_DERM_MUSP500 * q["scatter"], alpha, alpha,
                   ("roughness = %.4g\n" % alpha if self.a.rough else "")
                   + ("multiple_scattering = 1\n" if self.a.multiple else "")
                   + ("macro_slope = %.4g\n" % q["macro"] if q.get("macro", 0) > 0 else "")))

    def bake(self, q):
        """Bake the Monte Carlo part (cached: roughness does not enter it)."""
        key = (q["sebum"], round(q["melanin"], 7), round(q["blood"], 7), round(q["scatter"], 6),
               round(q["alpha"], 6) if self.a.rough else 0, round(q.get("alpha_epi", 0.0), 6),
               round(q.get("macro", 0.0), 6))
        if key in self.cache:
            return self.cache[key]
        d = os.path.join(self.a.out, "bake%04d" % len(self.cache))
        ini = d + ".ini"
        with open(ini, "w") as f:
            f.write(self.preset_ini(q, q["alpha"] if self.a.rough else 0.3))
        cmd = [self.a.skinbake, "bake", "--preset-file", ini, "--out", d,
               "--theta-in", ",".join("%g" % t for t in TRAIN_THETA_I), "--wavelengths", "470,550,656",
               "--target-error", str(self.a.target_error), "--batch-photons", str(self.a.batch_photons),
               "--seed", "1", "--threads", str(self.a.threads), "--quiet", "--solver", "mc"]
        subprocess.run(cmd, check=True)
        with open(os.path.join(d, "manifest.json")) as f:
            self.seconds += json.load(f)["result"]["seconds"]
        self.n_bakes += 1
        self.cache[key] = d
        return d

    def eval_bake(self, d, alpha):
        with open(self.pts_file) as f:
            out = subprocess.run([self.a.brdf_points, d, "--alpha", "%.6g" % alpha], stdin=f,
                                 check=True, capture_output=True, text=True).stdout
        return parse_columns(out)

    def eval_ad(self, q):
        ini = os.path.join(self.a.out, "ad.ini")
        with open(ini, "w") as f:
            f.write(self.preset_ini(q, q["alpha"]))
        with open(self.pts_file) as f:
            acc = ["--nodes", str(self.a.nodes)] if self.a.nodes else ["--tol", str(self.a.tol)]
            out = subprocess.run([self.a.brdf_model, "--preset-file", ini] + acc, stdin=f,
                                 check=True, capture_output=True, text=True).stdout
        self.n_bakes += 1
        return parse_columns(out)

    def model_brdf(self, q):
        """THE evaluation: BRDF [1/sr] (mean of 470/550/656 nm) and its standard
        error at the training points for parameters q (melanin, blood, scatter,
        sebum, alpha), by Monte Carlo (a cached bake; alpha enters only the
        analytic lobe) or by adding-doubling."""
        if self.a.solver == "ad":
            return self.eval_ad(q)
        return self.eval_bake(self.bake(q), q["alpha"])


def parse_columns(out):
    tot, err = [], []
    for line in out.split("\n"):
        if line:
            c = line.split("\t")
            tot.append(float(c[0]))
            err.append(float(c[3]))
    return tot, err


LOG_OBJECTIVE = False


def objective(points, f, e):
    """Debiased mean squared relative error and its Monte Carlo standard deviation
    (--objective log: the mean squared log ratio ln(f / y), issue 21 round 7)."""
    s, v = 0.0, 0.0
    if LOG_OBJECTIVE:
        for p, fi, ei in zip(points, f, e):
            r, er = math.log(max(fi, 1e-12) / p[4]), ei / max(fi, 1e-12)
            s += r * r - er * er
            v += 4.0 * r * r * er * er
        n = len(points)
        return s / n, math.sqrt(v) / n
    for p, fi, ei in zip(points, f, e):
        r, er = (fi - p[4]) / p[4], ei / p[4]
        s += r * r - er * er
        v += 4.0 * r * r * er * er
    n = len(points)
    return s / n, math.sqrt(v) / n


def best_alpha(model, q, points, lo=0.02, hi=1.0):
    """Golden-section search for the roughness (with Monte Carlo, no new bake)."""
    g = (math.sqrt(5) - 1) / 2
    memo = {}

    def j(a):
        if a not in memo:
            memo[a] = objective(points, *model.model_brdf(dict(q, alpha=a)))
        return memo[a]
    a, b = lo, hi
    c1, c2 = b - g * (b - a), a + g * (b - a)
    while b - a > 0.005:
        if j(c1)[0] < j(c2)[0]:
            b, c2 = c2, c1
            c1 = b - g * (b - a)
        else:
            a, c1 = c1, c2
            c2 = a + g * (b - a)
    al = (a + b) / 2
    return al, j(al)


def to_params(x, sebum):
    q = {"sebum": sebum}
    for k, xi in zip(NAMES, x):
        lo, hi = BOUNDS[k]
        q[k] = min(max(math.exp(xi), lo), hi)
    return q


def nelder_mead(f, x0, steps, noise, max_evals):
    """Nelder-Mead (Lagarias et al. 1998 coefficients); f returns (value, sd)."""
    n = len(x0)
    simplex = [list(x0)] + [[x0[j] + (steps[j] if j == i else 0.0) for j in range(n)] for i in range(n)]
    vals = [f(x) for x in simplex]
    evals = n + 1
    while evals < max_evals:
        order = sorted(range(n + 1), key=lambda i: vals[i][0])
        simplex = [simplex[i] for i in order]
        vals = [vals[i] for i in order]
        spread = vals[-1][0] - vals[0][0]
        sd = max(v[1] for v in vals)
        size = max(abs(simplex[i][j] - simplex[0][j]) for i in range(1, n + 1) for j in range(n))
        if spread < noise * max(sd, 1e-6) or size < 0.01:
            break
        c = [sum(simplex[i][j] for i in range(n)) / n for j in range(n)]
        xr = [c[j] + (c[j] - simplex[-1][j]) for j in range(n)]
        fr = f(xr)
        evals += 1
        if fr[0] < vals[0][0]:
            xe = [c[j] + 2 * (c[j] - simplex[-1][j]) for j in range(n)]
            fe = f(xe)
            evals += 1
            simplex[-1], vals[-1] = (xe, fe) if fe[0] < fr[0] else (xr, fr)
        elif fr[0] < vals[-2][0]:
            simplex[-1], vals[-1] = xr, fr
        else:
            inside = fr[0] >= vals[-1][0]
            # outside contraction toward xr, or inside toward the worst point
            xc = [c[j] + (-0.5 if inside else 0.5) * (c[j] - simplex[-1][j]) for j in range(n)]
            fc = f(xc)
            evals += 1
            if fc[0] < min(fr[0], vals[-1][0]):
                simplex[-1], vals[-1] = xc, fc
            else:
                for i in range(1, n + 1):
                    simplex[i] = [simplex[0][j] + 0.5 * (simplex[i][j] - simplex[0][j]) for j in range(n)]
                    vals[i] = f(simplex[i])
                    evals += 1
    i = min(range(n + 1), key=lambda k: vals[k][0])
    return simplex[i], vals[i], evals


def evaluate(a, ini):
    """--evaluate: the preset file's BRDF by adding-doubling at all 205 CUReT
    points; RMS relative error on the training points, on the 181 held out
    (not training, not the 4 saturated grazing mirror points, idx 202-205),
    the back-side fall f(-78.75)/f(-33.75) at 11.25 deg and the forward
    rise f(78.75)/f(33.75) at 33.75 deg (in plane), as validate-brdf.sh."""
    rows = read_curet(a.curet)
    pts = os.path.join(a.out, "all-points.txt")
    os.makedirs(a.out, exist_ok=True)
    with open(pts, "w") as f:
        for r in rows:
            f.write("%g %g %g\n" % (r[1], r[2], r[3]))
    acc = ["--nodes", str(a.nodes)] if a.nodes else ["--tol", str(a.tol)]
    with open(pts) as f:
        out = subprocess.run([a.brdf_model, "--preset-file", ini] + acc, stdin=f, check=True,
                             capture_output=True, text=True).stdout
    sim, _ = parse_columns(out)
    sat = set(SATURATED)
    train = [(r, v) for r, v in zip(rows, sim) if r[1] in TRAIN_THETA_I]
    held = [(r, v) for r, v in zip(rows, sim) if r[1] not in TRAIN_THETA_I and r[0] not in sat]

    def rms(sel):
        return 100 * math.sqrt(sum(((v - r[4]) / r[4]) ** 2 for r, v in sel) / len(sel))

    def at(ti, tv, dphi):
        for r, v in zip(rows, sim):
            if abs(r[1] - ti) < 0.01 and abs(r[2] - tv) < 0.01 and abs(r[3] - dphi) < 0.01:
                return v, r[4]
        return None
    b1, b0 = at(11.25, 78.75, 0), at(11.25, 33.75, 0)
    f1, f0 = at(33.75, 78.75, 180), at(33.75, 33.75, 180)
    worst = max(held, key=lambda rv: abs(rv[1] - rv[0][4]) / rv[0][4])
    print("# %s: RMS relative %.1f %% on the %d training points, %.1f %% on the %d held out "
          "(theta_i < 60: %.1f %%, >= 60: %.1f %%); back-side fall %.2f (CUReT %.2f), forward rise %.2f "
          "(CUReT %.2f); worst held out idx %d (ti %.2f tv %.2f dphi %.2f) %+.0f %%"
          % (os.path.basename(ini), rms(train), len(train), rms(held), len(held),
             rms([h for h in held if h[0][1] < 60]), rms([h for h in held if h[0][1] >= 60]),
             b1[0] / b0[0], b1[1] / b0[1], f1[0] / f0[0], f1[1] / f0[1], worst[0][0], worst[0][1],
             worst[0][2], worst[0][3], 100 * (worst[1] - worst[0][4]) / worst[0][4]))
    if a.residuals:
        ang = {}
        with open(a.curet) as f:
            for line in f:
                if not (line.startswith("#") or line.startswith("idx")):
                    c = line.split("\t")
                    ang[int(c[0])] = float(c[5])
        residuals(rows, sim, ang, sat)
        return
    for r, v in zip(rows, sim):
        print("%d\t%g\t%g\t%g\t%g\t%.5g\t%s" % (r[0], r[1], r[2], r[3], r[4], v,
              "train" if r[1] in TRAIN_THETA_I else "sat" if r[0] in sat else "held"))


def reciprocal_pairs(rows):
    """CUReT's reciprocal pairs: (a, b) with theta_i and theta_v swapped and the
    same azimuth difference (within the table's rounding, 0.6 and 1.5 deg)."""
    out = []
    for a in rows:
        for b in rows:
            if a[0] < b[0] and abs(a[1] - b[2]) < 0.6 and abs(a[2] - b[1]) < 0.6 and abs(a[3] - b[3]) < 1.5:
                out.append((a, b))
    return out


def region(r):
    """low: both angles under 60 deg; else back (dphi < 90) or mirror side."""
    if max(r[1], r[2]) < 60:
        return "low"
    return "back" if r[3] < 90 else "mirror"


def asperity(ti, tv, dphi, g, tau):
    """Single scattering in an optically thin layer of sparse scatterers above
    the skin (Koenderink & Pont 2003, "The secret of velvety skin", Machine
    Vision and Applications 14: 260-268), albedo 1, Henyey-Greenstein phase g,
    optical depth tau, unnormalised: p(cos) (1 - exp(-tau (1/mi + 1/mo))) / (mi + mo)."""
    mi, mo = math.cos(math.radians(ti)), math.cos(math.radians(tv))
    si, so = math.sin(math.radians(ti)), math.sin(math.radians(tv))
    c = -(mi * mo + si * so * math.cos(math.radians(dphi)))     # cosine of the scattering angle
    p = (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * c) ** 1.5)
    return p * (1 - math.exp(-tau * (1 / mi + 1 / mo))) / (mi + mo)


def residuals(rows, sim, ang, sat):
    """--residuals: the data's own uncertainty and where the misses sit (markdown)."""
    res = {r[0]: (v - r[4]) / r[4] for r, v in zip(rows, sim)}
    kind = {r[0]: ("train" if r[1] in TRAIN_THETA_I else "sat" if r[0] in sat else "held") for r in rows}
    held = [r for r in rows if kind[r[0]] == "held"]

    def rms(v):
        return 100 * math.sqrt(sum(x * x for x in v) / len(v)) if v else float("nan")

    def mean(v):
        return 100 * sum(v) / len(v) if v else float("nan")
    pairs = reciprocal_pairs(rows)
    d = {"low": [], "back": [], "mirror": []}
    for a, b in pairs:
        d[region(a)].append((a[4] - b[4]) / (0.5 * (a[4] + b[4])))
    alld = [x for v in d.values() for x in v]
    # A reciprocal model cannot do better on a pair than its mean: half the difference each.
    floor = [(0.5 * (a[4] - b[4])) / r[4] for a, b in pairs for r in (a, b) if kind[r[0]] == "held"]
    pm = {}
    for a, b in pairs:
        pm[a[0]] = pm[b[0]] = 0.5 * (a[4] + b[4])
    simd = {r[0]: v for r, v in zip(rows, sim)}
    vs_mean = [(simd[r[0]] - pm.get(r[0], r[4])) / pm.get(r[0], r[4]) for r in held]
    quant = [0.0005 / math.sqrt(3) / r[4] for r in held]     # 3 decimals: uniform rounding error
    print("## residuals")
    print("reciprocal pairs: %d (%s); the relative difference between the two readings of a pair, RMS: "
          "%.1f %% (per reading %.1f %%, the difference over sqrt 2)" % (
              len(pairs), ", ".join("%d %s" % (len(v), k) for k, v in d.items()), rms(alld), rms(alld) / math.sqrt(2)))
    print("")
    print("| where | pairs | RMS difference within a pair [%] | per reading [%] | largest [%] |")
    print("|---|---|---|---|---|")
    for k, v in d.items():
        print("| %s | %d | %.1f | %.1f | %.1f |" % (k, len(v), rms(v), rms(v) / math.sqrt(2),
                                                   100 * max(abs(x) for x in v) if v else float("nan")))
    print("")
    print("floor: a reciprocal model's RMS over the %d held-out points from the %d of them in pairs: %.1f %%; "
          "the table's 3 decimals: %.2f %%; held out against the pair means instead of the readings: %.1f %% "
          "(against the readings %.1f %%)" % (len(held), len(floor), rms(floor + [0.0] * (len(held) - len(floor))),
                                             rms(quant), rms(vs_mean), rms([res[r[0]] for r in held])))
    print("")
    print("| held-out points | n | mean relative error [%] | RMS [%] |")
    print("|---|---|---|---|")
    for k in ("low", "back", "mirror"):
        v = [res[r[0]] for r in held if region(r) == k]
        print("| %s | %d | %+.1f | %.1f |" % ({"low": "both angles < 60°", "back": "≥ 60°, back side (Δφ < 90°)",
                                              "mirror": "≥ 60°, mirror side"}[k], len(v), mean(v), rms(v)))
    print("")
    print("| angle between light and camera | training: n, mean, RMS [%] | held out, both angles < 60°: n, mean, RMS [%] | held out, all: n, mean, RMS [%] |")
    print("|---|---|---|---|")
    for g in sorted(set(ang.values())):
        cells = []
        for sel in (lambda r: kind[r[0]] == "train", lambda r: kind[r[0]] == "held" and region(r) == "low",
                    lambda r: kind[r[0]] == "held"):
            v = [res[r[0]] for r in rows if ang[r[0]] == g and sel(r)]
            cells.append("%d, %+.1f, %.1f" % (len(v), mean(v), rms(v)) if v else "-")
        if cells == ["-", "-", "-"]:
            continue        # only saturated points there
        print("| %.1f° | %s |" % (g, " | ".join(cells)))
    print("")
    # Asperity scattering as an added term, the skin part as evaluated (scaled by s).
    grid = [(g, tau, k, sc) for g in (0.0, 0.3, 0.6, 0.8, 0.9, 0.95) for tau in (0.01, 0.05, 0.2, 1.0)
            for k in (0.0, 0.25, 0.5, 1, 2, 4, 8) for sc in (0.85, 0.9, 0.95, 1.0)]

    def fit(sel):
        best = None
        for g, tau, k, sc in grid:
            v = [((simd[r[0]] * sc + k * asperity(r[1], r[2], r[3], g, tau)) - r[4]) / r[4] for r in rows if sel(r)]
            j = rms(v)
            if best is None or j < best[0]:
                best = (j, g, tau, k, sc)
        return best

    def held_with(b):
        _, g, tau, k, sc = b
        return (rms([((simd[r[0]] * sc + k * asperity(r[1], r[2], r[3], g, tau)) - r[4]) / r[4] for r in held]),
                rms([((simd[r[0]] * sc + k * asperity(r[1], r[2], r[3], g, tau)) - r[4]) / r[4] for r in rows
                     if kind[r[0]] == "train"]))
    bt = fit(lambda r: kind[r[0]] == "train")
    ba = fit(lambda r: kind[r[0]] != "sat")
    print("asperity: fitted on the training points: amplitude %g, g %g, tau %g, scale %g: training %.1f %%, held out %.1f %%; "
          "fitted on every point but the saturated ones (a diagnostic): amplitude %g, g %g, tau %g, scale %g: training "
          "%.1f %%, held out %.1f %%" % (bt[3], bt[1], bt[2], bt[4], held_with(bt)[1], held_with(bt)[0],
                                          ba[3], ba[1], ba[2], ba[4], held_with(ba)[1], held_with(ba)[0]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--skinbake", default="./skinbake")
    ap.add_argument("--brdf-points", default="./tests/brdf_points")
    ap.add_argument("--curet", default=None, help="curet_sample39_brdf_205.tsv")
    ap.add_argument("--out", default="fit-curet-work", help="scratch directory")
    ap.add_argument("--brdf-model", default="./tests/brdf_model")
    ap.add_argument("--solver", default="mc", choices=("mc", "ad"),
                    help="mc: skinbake bake + brdf_points; ad: brdf_model (adding-doubling)")
    ap.add_argument("--target-error", type=float, default=0.02, help="bake target RMS relative error")
    ap.add_argument("--batch-photons", type=int, default=2000)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--max-evals", type=int, default=None, help="evaluations per simplex (default 60 mc, 400 ad)")
    ap.add_argument("--log", default=None, help="also write the evaluation log here (TSV)")
    ap.add_argument("--blood-max", type=float, default=None, help="upper bound of the blood fraction (default 0.07)")
    ap.add_argument("--rough", action="store_true",
                    help="the roughness is also the transport's rough top boundary ([surface] roughness)")
    ap.add_argument("--multiple", action="store_true",
                    help="with --rough: light scatters on the facets until it leaves (Heitz 2016)")
    ap.add_argument("--rough-epi", action="store_true",
                    help="with --rough and the film: the epidermis top under the film is rough too, with its own "
                    "alpha ([epidermis] top_roughness; the film's top is [surface] roughness)")
    ap.add_argument("--macro", action="store_true",
                    help="fit the RMS slope of a mm-scale relief too ([surface] macro_slope, engine/macro.h)")
    ap.add_argument("--tol", type=float, default=0.01,
                    help="--solver ad: the solver's tolerance (table RMS relative error estimate)")
    ap.add_argument("--nodes", type=int, default=32,
                    help="--solver ad: one solve at this many nodes per unit cosine (0: --tol instead; 32 is "
                    "within 1.1 %% of 64 at the training points with two rough interfaces)")
    ap.add_argument("--sebum", default="both", choices=("on", "off", "both"), help="films to fit")
    ap.add_argument("--start", default=None,
                    help="starting point melanin,blood,scatter,alpha[,alpha_epi[,macro]] (default 0.025,0.02,1,0.35; "
                    "macro 0.1)")
    ap.add_argument("--train", default="low", choices=("low", "all"),
                    help="low: the 20 points at 11.25/33.75 deg (the fit); all: every point but the 4 "
                    "saturated ones (a diagnostic of the model's best, not a fit to report as held out)")
    ap.add_argument("--residuals", action="store_true",
                    help="with --evaluate: instead of the points, the data's own uncertainty (CUReT's reciprocal "
                    "pairs) and the residuals by region and by the angle between light and camera (markdown)")
    ap.add_argument("--evaluate", default=None, metavar="INI",
                    help="no fit: the preset file at all 205 points (adding-doubling), its errors, fall and rise")
    ap.add_argument("--step-scale", type=float, default=1.0,
                    help="scale on the simplex's first steps (ln 3, ln 3, ln 1.5, ln 1.5 ...); < 1 to refine near --start")
    ap.add_argument("--objective", default="rel", choices=("rel", "log"),
                    help="rel: mean squared relative error (default); log: mean squared ln(f / y)")
    a = ap.parse_args()
    global LOG_OBJECTIVE
    LOG_OBJECTIVE = a.objective == "log"
    if a.rough_epi and not a.rough:
        sys.exit("fit-curet: --rough-epi needs --rough")
    if a.rough_epi and a.sebum == "both":
        a.sebum = "on"      # without the film there is no boundary under it
    if a.blood_max is not None:
        BOUNDS["blood"] = (BOUNDS["blood"][0], a.blood_max)
    if a.max_evals is None:
        a.max_evals = 400 if a.solver == "ad" else 60
    if a.curet is None:
        for d in (os.path.join(here, "..", "..", "shared", "skin_data"), "/work/shared/skin_data"):
            if os.path.exists(os.path.join(d, "curet_sample39_brdf_205.tsv")):
                a.curet = os.path.join(d, "curet_sample39_brdf_205.tsv")
                break
    if a.curet is None:
        sys.exit("fit-curet: give --curet PATH/curet_sample39_brdf_205.tsv")
    if a.evaluate:
        evaluate(a, a.evaluate)
        return
    t_start = time.time()
    if a.train == "all":    # diagnostic: what the model can do at best on every point
        points = [r for r in read_curet(a.curet) if r[0] not in SATURATED]
    else:
        points = [r for r in read_curet(a.curet) if r[1] in TRAIN_THETA_I]
    model = Model(a, points)
    log = open(a.log, "w") if a.log else None
    hdr = "eval\tsebum\tmelanin\tblood\tscatter\talpha\talpha_epi\tJ\tJ_sd\trms_rel_pct" + ("\tmacro" if a.macro else "")
    print(hdr)
    if log:
        log.write("# scripts/fit-curet.py: %d training points (%s), solver %s, bake target %g, bounds %s\n"
                  % (len(points), "--train all: every CUReT point but the 4 saturated ones" if a.train == "all"
                     else "CUReT theta_i " + "/".join("%g" % t for t in TRAIN_THETA_I), a.solver, a.target_error,
                     ", ".join("%s %g-%g" % (k, v[0], v[1]) for k, v in BOUNDS.items())))
        log.write(hdr + "\n")
    k = [0]

    def f(x, sebum):
        q = to_params(x, sebum)
        if "alpha" in NAMES:     # adding-doubling or --rough: the roughness in the simplex too
            j, sd = objective(points, *model.model_brdf(q))
        else:               # Monte Carlo: a 1-D search per (cached) bake
            q["alpha"], (j, sd) = best_alpha(model, q, points)
        k[0] += 1
        line = "%d\t%d\t%.5f\t%.5f\t%.4f\t%.3f\t%.3f\t%.6f\t%.6f\t%.2f" % (
            k[0], sebum, q["melanin"], q["blood"], q["scatter"], q["alpha"], q.get("alpha_epi", 0.0), j, sd,
            100 * math.sqrt(max(j, 0))) + ("\t%.4f" % q["macro"] if a.macro else "")
        print(line, flush=True)
        if log:
            log.write(line + "\n")
            log.flush()
        # Out of bounds: the clamped value plus a penalty keeps the simplex inside.
        pen = sum(max(0.0, abs(xi - math.log(min(max(math.exp(xi), BOUNDS[kk][0]), BOUNDS[kk][1]))))
                  for xi, kk in zip(x, NAMES))
        return j + pen, sd
    st = [float(v) for v in a.start.split(",")] if a.start else [0.025, 0.02, 1.0, 0.35]
    x0 = [math.log(st[0]), math.log(st[1]), math.log(st[2])]     # medium skin, scattering as measured
    steps = [math.log(3.0), math.log(3.0), math.log(1.5)]
    joint = a.solver == "ad" or a.rough      # the roughness needs its own solve or bake
    if joint:
        NAMES.append("alpha")
        x0.append(math.log(st[3]))
        steps.append(math.log(1.5))
    if a.rough_epi:
        NAMES.append("alpha_epi")
        x0.append(math.log(st[4] if len(st) > 4 else st[3]))
        steps.append(math.log(1.5))
    if a.macro:
        NAMES.append("macro")
        x0.append(math.log(st[5] if len(st) > 5 else 0.1))
        steps.append(math.log(2.0))
    steps = [v * a.step_scale for v in steps]
    best = None
    for sebum in {"on": (1,), "off": (0,), "both": (1, 0)}[a.sebum]:
        x, (j, sd), n = nelder_mead(lambda xx: f(xx, sebum), x0, steps, 3.0, a.max_evals)
        q = to_params(x, sebum)
        if joint:
            j, sd = objective(points, *model.model_brdf(q))
        else:
            q["alpha"], (j, sd) = best_alpha(model, q, points)
        print("# sebum %s: J %.6f +- %.6f (RMS relative %.2f %%) after %d evaluations"
              % ("on" if sebum else "off", j, sd, 100 * math.sqrt(max(j, 0)), n), flush=True)
        if best is None or j < best[0]:
            best = (j, sd, q)
    j, sd, q = best
    summary = ("# best: sebum %s, melanin %.4g, blood %.4g, scatter %.3g, alpha %.3g, alpha_epi %.3g, macro %.3g: "
               "RMS relative %.2f %% "
               "(J %.6f +- %.6f) on %d training points; solver %s: %d bakes or solves (%.0f s of bake time), %.0f s in all"
               % ("on" if q["sebum"] else "off", q["melanin"], q["blood"], q["scatter"], q["alpha"],
                  q.get("alpha_epi", 0.0), q.get("macro", 0.0), 100 * math.sqrt(max(j, 0)), j, sd, len(points), a.solver,
                  model.n_bakes, model.seconds,
                  time.time() - t_start))
    print(summary)
    print(model.preset_ini(q, q["alpha"]))
    if log:
        log.write(summary + "\n")
        log.close()


if __name__ == "__main__":
    main()
