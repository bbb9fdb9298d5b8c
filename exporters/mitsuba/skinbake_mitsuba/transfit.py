"""The translucent mode's medium: one homogeneous medium per colour channel under
the bake's rough top, fitted to the bake's Rd(r), and its own BRDF baked.

Mitsuba 3 has no BSSRDF. The translucent mode puts a homogeneous medium inside
the closed mesh, under a rough dielectric surface (the bake's GGX alpha, the
index of the bake's top scattering layer), isotropic phase function; per colour
channel (the bake wavelength with the largest weight in it, as the volumetric
mode) two numbers: the single-scattering albedo a and the extinction mu_t.
  * a sets the power of the reflected profile, mu_t scales its lengths: the fit
    makes the medium's power and mean exit radius within the bake's profile
    (r < n_r dr) equal the bake's (the same rule as src/export/sss_fit.h for
    POV-Ray and Cycles).
  * The medium's R(r) is computed by skinbake simulate (Monte Carlo, the rough
    top with single scattering on the facets, as Mitsuba's roughdielectric) at
    mu_t = 1 / cm: R(r) at mu_t is mu_t^2 R_1(mu_t r), so one run per albedo
    gives every mu_t. tests/mitsuba_translucent.sh measures the fitted medium's
    R(r) in Mitsuba itself (transmeasure.py) against the bake's.
  * The medium's own BRDF (the light it returns from a laterally uniform beam)
    is baked by skinbake bake --solver ad from a preset file of that medium
    ([skin] model = tables): the BSDF (transbsdf.py) adds the bake's table minus
    that BRDF, so a flat surface under a distant light shows the bake's BRDF.
fit.json holds the fit; medium/ the medium's bake.
"""
import math
import os
import subprocess

import numpy as np

from . import json_dump, json_load, json_loads

PHOTONS = 100000
R_STEP_MFP = 0.02       # radial bin at mu_t = 1 / cm [cm]
R_BINS = 4000           # to 80 mean free paths


def _profile_target(man, k):
    rad = man["radial"]
    dr = float(rad["dr_cm"])
    rd = np.array(rad["rd_r"][k], dtype=float)
    edges = dr * np.arange(len(rd) + 1)
    area = math.pi * (edges[1:] ** 2 - edges[:-1] ** 2)
    power = float(np.sum(rd * area))
    mean_r = float(rad["mean_radius_cm"][k])
    return power, mean_r, dr * len(rd)


def _simulate(skinbake, albedo, n, alpha, photons, seed=1):
    """R_1(r) at mu_t = 1/cm: (bin edges [cm], ring powers)."""
    layer = "d=inf,n=%.9g,mua=%.12g,mus=%.12g,g=0,rough=%.9g" % (n, 1.0 - albedo, albedo, alpha)
    cmd = [skinbake, "simulate", "--layer", layer, "--n-below", "%.9g" % n,
           "--photons", str(photons), "--seed", str(seed), "--r-step", "%g" % R_STEP_MFP,
           "--r-bins", str(R_BINS), "--json"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    js = json_loads(out)
    vals = np.array(js["Rd_r"]["rd_per_cm2"], dtype=float)
    edges = np.array(js["Rd_r"]["r_edges_cm"], dtype=float)
    ring = vals * math.pi * (edges[1:] ** 2 - edges[:-1] ** 2)
    return edges, ring, js


def _within(edges, ring, x):
    """Power and first moment of the profile within radius x (bins split by area)."""
    c = np.concatenate([[0.0], np.cumsum(ring)])
    m = np.concatenate([[0.0], np.cumsum(ring * 0.5 * (edges[1:] + edges[:-1]))])
    p = np.interp(x, edges, c)
    mom = np.interp(x, edges, m)
    return p, mom


def _mu_t_for_mean(edges, ring, r_max, mean_target):
    """mu_t [1/cm] whose mean radius within r_max is mean_target (bisection in log mu_t)."""
    lo, hi = 1e-2, 1e5
    for _ in range(80):
        mid = math.sqrt(lo * hi)
        p, mom = _within(edges, ring, mid * r_max)
        mean = (mom / p) / mid if p > 0 else 0.0
        # larger mu_t: shorter lengths
        if mean > mean_target:
            lo = mid
        else:
            hi = mid
    return math.sqrt(lo * hi)


def fit_channel(skinbake, power_t, mean_t, r_max, n, alpha, photons=PHOTONS):
    """(albedo, mu_t [1/cm], power, mean radius) of the medium matching the
    bake's power and mean radius within r_max."""
    lo, hi = 0.0, 1.0 - 1e-6
    best = None
    for _ in range(18):
        a = 0.5 * (lo + hi)
        edges, ring, _ = _simulate(skinbake, a, n, alpha, photons)
        mu = _mu_t_for_mean(edges, ring, r_max, mean_t)
        p, mom = _within(edges, ring, mu * r_max)
        best = (a, mu, p, (mom / p) / mu)
        if p < power_t:
            lo = a
        else:
            hi = a
        if abs(p - power_t) < 2e-4 * max(power_t, 1e-3):
            break
    return best


def _preset(path, man, media, alpha, n):
    """A preset file ([skin] model = tables) of the medium at the bake's wavelengths."""
    lines = ["; written by skinbake_mitsuba fit: the translucent mode's homogeneous medium",
             "[skin]", "base = paper", "name = translucent-medium", "model = tables",
             "[sebum]", "thickness = 0", "[dermis]", "thickness = inf",
             "[surface]", "roughness = %.9g" % alpha]
    for wl, (mua, mus) in zip(man["wavelengths_nm"], media):
        lines.append("[override.%g]" % wl)
        for layer in ("epidermis", "dermis"):
            lines += ["%s.mua = %.9g" % (layer, mua), "%s.mus = %.9g" % (layer, mus),
                      "%s.g = 0" % layer, "%s.n = %.9g" % (layer, n)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def fit(bake, out, skinbake="skinbake", photons=PHOTONS, log=None):
    """Fit the medium per channel of BAKE, bake its BRDF; write OUT/fit.json and
    OUT/medium/ (a bake directory). Returns the fit as a dict."""
    with open(os.path.join(bake, "manifest.json")) as f:
        man = json_load(f)
    if "radial" not in man or not man["radial"].get("rd_r"):
        raise ValueError("%s: the bake has no radial profile (radial.rd_r), which the translucent "
                         "mode is fitted to" % bake)
    alpha = float(man["specular"]["alpha"])
    if alpha <= 0.0:
        raise ValueError("%s: specular.alpha is 0: the translucent mode needs a rough top "
                         "(alpha in (0, 1])" % bake)
    layers = man["layers"]
    nw = len(man["wavelengths_nm"])
    rgb_from_wl = np.array(man["rgb"]["rgb_from_wl"]).reshape(3, nw)
    chan_wl = [int(np.argmax(rgb_from_wl[c])) for c in range(3)]
    # the index of the first scattering layer (under the clear films)
    n = None
    for ly in layers[0]["layers"]:
        if ly["mua_per_cm"] > 0 or ly["mus_per_cm"] > 0:
            n = float(ly["n"])
            break
    channels = []
    media = [None] * nw
    for c, k in enumerate(chan_wl):
        power_t, mean_t, r_max = _profile_target(man, k)
        a, mu, p, m = fit_channel(skinbake, power_t, mean_t, r_max, n, alpha, photons)
        ch = {"channel": "RGB"[c], "wavelength_nm": man["wavelengths_nm"][k], "albedo": a,
              "mu_t_per_cm": mu, "mua_per_cm": (1.0 - a) * mu, "mus_per_cm": a * mu, "g": 0.0,
              "bake_power": power_t, "medium_power": p, "bake_mean_radius_cm": mean_t,
              "medium_mean_radius_cm": m, "r_max_cm": r_max}
        channels.append(ch)
        media[k] = ((1.0 - a) * mu, a * mu)
        if log:
            log("channel %s (%g nm): albedo %.6f, mu_t %.4g /cm; power %.4f (bake %.4f), "
                "mean radius %.4g cm (bake %.4g)"
                % ("RGB"[c], ch["wavelength_nm"], a, mu, p, power_t, m, mean_t))
    # wavelengths no channel uses: the nearest channel's medium (the bake needs every one)
    for k in range(nw):
        if media[k] is None:
            wls = man["wavelengths_nm"]
            near = min(chan_wl, key=lambda j: abs(wls[j] - wls[k]))
            media[k] = media[near]
    os.makedirs(out, exist_ok=True)
    ini = os.path.join(out, "medium.ini")
    _preset(ini, man, media, alpha, n)
    medium = os.path.join(out, "medium")
    cmd = [skinbake, "bake", "--preset-file", ini, "--solver", "ad", "--ad-quad", "128",
           "--ad-tol", "0.01", "--quiet", "--out", medium]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    res = {"format": "skinbake-mitsuba-translucent", "bake": os.path.abspath(bake), "n": n,
           "alpha": alpha, "photons": photons, "channels": channels, "chan_wl": chan_wl,
           "medium_bake": "medium"}
    with open(os.path.join(out, "fit.json"), "w") as f:
        json_dump(res, f, indent=1)
    return res
