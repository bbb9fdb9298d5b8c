"""Command line of skinbake_mitsuba. Bad input: a message naming the option, the
value and the allowed range on stderr, exit status 2, no output."""
import argparse
import math
import sys
import time

from . import json_dump
from . import stack as stk
from . import variant

USAGE_ERROR = 2


class UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def _floats(text, name, lo, hi, unit):
    out = []
    for item in text.split(","):
        try:
            v = float(item)
        except ValueError:
            raise UsageError("%s: '%s' is not a number" % (name, item)) from None
        if not (lo <= v <= hi):
            raise UsageError("%s %g is outside [%g, %g] %s" % (name, v, lo, hi, unit))
        out.append(v)
    return out


def _int_range(name, v, lo, hi):
    if not (lo <= v <= hi):
        raise UsageError("%s %d is outside [%d, %d]" % (name, v, lo, hi))


def _slab_parser(sub):
    p = sub.add_parser("slab", help="measure Rd(theta), Rd(r) rings and BRDF points of a flat "
                       "layer stack with Mitsuba's volumetric path tracer (JSON on stdout)")
    p.add_argument("--layer", action="append", required=True,
                   help="d=CM,n=..,mua=1/CM,mus=1/CM,g=.. as skinbake simulate, top first")
    p.add_argument("--n-above", type=float, default=1.0, help="index above (default 1)")
    p.add_argument("--n-below", type=float, default=None, help="index below (default: last layer's)")
    p.add_argument("--theta-in", default="", help="incidence angles for Rd, deg in [0, 89], comma separated")
    p.add_argument("--rings", default="", help="ring edges in cm (ascending, from 0), comma separated")
    p.add_argument("--band", action="append", default=[],
                   help="THETA_VIEW,THETA_LO,THETA_HI in deg: the azimuthal-mean BRDF between the view "
                   "and light from the polar band (repeat; the band must not hold the view angle)")
    p.add_argument("--spp", type=int, default=4096, help="paths per batch in [16, 1e7]")
    p.add_argument("--batches", type=int, default=8, help="independent batches in [2, 1000]")
    p.add_argument("--variant", default=None, help="Mitsuba variant (default llvm_ad_mono, else scalar)")
    return p


def _check_slab(a):
    try:
        layers = [stk.parse_layer(s) for s in a.layer]
    except ValueError as e:
        raise UsageError(str(e)) from None
    for name, v in (("--n-above", a.n_above), ("--n-below", a.n_below)):
        if v is not None and not (1.0 <= v <= 10.0):
            raise UsageError("%s %g is outside [1, 10]" % (name, v))
    if any(math.isinf(ly.d) for ly in layers):
        raise UsageError("--layer d=inf: the slab needs finite layers (use a thick last layer)")
    _int_range("--spp", a.spp, 16, 10 ** 7)
    _int_range("--batches", a.batches, 2, 1000)
    thetas = _floats(a.theta_in, "--theta-in", 0.0, 89.0, "deg") if a.theta_in else []
    rings = _floats(a.rings, "--rings", 0.0, stk.HALF_WIDTH_CM / 4, "cm") if a.rings else []
    if rings and (rings[0] != 0.0 or any(r1 <= r0 for r0, r1 in zip(rings, rings[1:]))):
        raise UsageError("--rings %s: edges must start at 0 and ascend" % a.rings)
    points = []
    for text in a.band:
        v = _floats(text, "--band", 0.0, 90.0, "deg")
        if len(v) != 3 or v[0] >= 89.0 or v[1] >= v[2] or v[1] <= v[0] <= v[2]:
            raise UsageError("--band %s: needs THETA_VIEW,THETA_LO,THETA_HI with theta_view < 89, "
                             "theta_lo < theta_hi and theta_view outside the band" % text)
        points.append(v)
    return layers, thetas, rings, points


def cmd_slab(a):
    layers, thetas, rings, points = _check_slab(a)
    used = variant.choose("mono", a.variant)
    from . import measure
    t0 = time.time()
    out = {"variant": used, "spp": a.spp, "batches": a.batches,
           "max_depth": stk.max_depth(layers), "rd": [], "rings": [], "brdf": []}
    for th in thetas:
        rd, err, rsp = measure.rd_theta(layers, th, a.spp, a.batches, a.n_above, a.n_below)
        out["rd"].append({"theta_in_deg": th, "Rd": rd, "Rd_err": err, "Rsp": rsp})
    for r0, r1 in zip(rings, rings[1:]):
        v, err = measure.rd_ring(layers, r0, r1, a.spp, a.batches, a.n_above, a.n_below)
        out["rings"].append({"r0_cm": r0, "r1_cm": r1, "power": v, "power_err": err})
    for tv, lo, hi in points:
        v, err = measure.brdf_band(layers, tv, lo, hi, a.spp, a.batches, a.n_above, a.n_below)
        out["brdf"].append({"theta_view_deg": tv, "theta_lo_deg": lo, "theta_hi_deg": hi,
                            "fr": v, "fr_err": err})
    out["seconds"] = time.time() - t0
    json_dump(out, sys.stdout)
    sys.stdout.write("\n")
    return 0


def _sphere_parser(sub):
    p = sub.add_parser("sphere", help="render a unit sphere with the baked table under a directional "
                       "light, orthographic from +z (the per-pixel check against skinbake eval)")
    p.add_argument("--bake", required=True, help="a directory written by skinbake bake")
    p.add_argument("--light-dir", default="0.5,0.3,0.8", help="direction toward the light, x,y,z")
    p.add_argument("--size", type=int, default=48, help="image width and height in [4, 4096] px")
    p.add_argument("--spp", type=int, default=256, help="samples per pixel in [1, 1e6]")
    p.add_argument("--wavelength", type=float, default=None,
                   help="nm in [360, 830]: render that 1 nm band in a spectral variant (default: rgb)")
    p.add_argument("--variant", default=None, help="Mitsuba variant (default llvm_ad_spectral or llvm_ad_rgb)")
    p.add_argument("--out", required=True, help="output .npy (float32 [size][size][channels])")
    return p


def cmd_sphere(a):
    import os
    if not os.path.isfile(os.path.join(a.bake, "manifest.json")):
        raise UsageError("--bake %s: no manifest.json there (not a bake directory)" % a.bake)
    d = _floats(a.light_dir, "--light-dir", -1e9, 1e9, "")
    if len(d) != 3 or (d[0] ** 2 + d[1] ** 2 + d[2] ** 2) == 0.0:
        raise UsageError("--light-dir %s: needs three numbers, not all 0" % a.light_dir)
    _int_range("--size", a.size, 4, 4096)
    _int_range("--spp", a.spp, 1, 10 ** 6)
    if a.wavelength is not None and not (360.0 <= a.wavelength <= 830.0):
        raise UsageError("--wavelength %g is outside [360, 830] nm" % a.wavelength)
    from . import sphere
    import numpy as np
    img, seconds, used = sphere.render(a.bake, d, a.size, a.spp, a.wavelength, a.variant)
    np.save(a.out, img.astype(np.float32))
    sys.stderr.write("skinbake_mitsuba sphere: %s, %dx%d at %d spp in %.2f s\n" % (used, a.size, a.size, a.spp, seconds))
    return 0


def _render_parser(sub):
    p = sub.add_parser("render", help="render a `skinbake export mitsuba` directory")
    p.add_argument("export", help="the directory written by skinbake export mitsuba")
    p.add_argument("--mode", default="table",
                   help="table, volumetric or translucent (default table)")
    p.add_argument("--fit", default=None,
                   help="translucent mode: the directory `fit` wrote for the skin's bake")
    p.add_argument("--width", type=int, default=None, help="image width in [8, 8192] px (default the scene's)")
    p.add_argument("--spp", type=int, default=64, help="samples per pixel in [1, 1e6]")
    p.add_argument("--seed", type=int, default=0, help="sampler seed in [0, 2^31-1] (default 0)")
    p.add_argument("--estimator", default="exit",
                   help="volumetric and translucent modes: exit (the light estimated through the "
                   "rough top at every medium vertex, exitnee.py) or volpath (Mitsuba's)")
    p.add_argument("--variant", default=None, help="Mitsuba variant (default llvm_ad_rgb, else scalar_rgb)")
    p.add_argument("--out", required=True, help="output image: .exr (linear) or .png (sRGB)")
    return p


def cmd_render(a):
    import os
    if a.mode not in ("table", "volumetric", "translucent"):
        raise UsageError("--mode %s is not table, volumetric or translucent" % a.mode)
    fitted = a.fit is not None and os.path.isfile(os.path.join(a.fit, "fit.json"))
    if a.mode == "translucent" and not fitted:
        raise UsageError("--mode translucent needs --fit DIR with fit.json "
                         "(python -m skinbake_mitsuba fit), "
                         "got %s" % a.fit)
    if not os.path.isfile(os.path.join(a.export, "manifest.json")):
        raise UsageError("%s: no manifest.json there (not a skinbake export mitsuba directory)" % a.export)
    if a.width is not None:
        _int_range("--width", a.width, 8, 8192)
    _int_range("--spp", a.spp, 1, 10 ** 6)
    _int_range("--seed", a.seed, 0, 2 ** 31 - 1)
    if a.estimator not in ("exit", "volpath"):
        raise UsageError("--estimator %s is not exit or volpath" % a.estimator)
    if not (a.out.endswith(".exr") or a.out.endswith(".png")):
        raise UsageError("--out %s: give a .exr or .png name" % a.out)
    from . import scene
    try:
        seconds, used = scene.render(a.export, a.mode, a.out, a.width, a.spp, a.variant, a.seed,
                                     a.fit, a.estimator)
    except ValueError as e:
        raise UsageError(str(e)) from None
    sys.stderr.write("skinbake_mitsuba render: %s mode, %s, %d spp, %.1f s\n" % (a.mode, used, a.spp, seconds))
    return 0


def _fit_parser(sub):
    p = sub.add_parser("fit", help="fit the translucent mode's medium to a bake's Rd(r) per "
                       "colour channel and bake the medium's own BRDF (transfit.py)")
    p.add_argument("--bake", required=True,
                   help="a directory written by skinbake bake (with its radial profile)")
    p.add_argument("--out", required=True, help="output directory (fit.json, medium.ini, medium/)")
    p.add_argument("--skinbake", default="skinbake",
                   help="the skinbake program (default: skinbake on PATH)")
    p.add_argument("--photons", type=int, default=100000,
                   help="Monte Carlo photons per profile in [1000, 1e8]")
    return p


def cmd_fit(a):
    import os
    import shutil
    if not os.path.isfile(os.path.join(a.bake, "manifest.json")):
        raise UsageError("--bake %s: no manifest.json there (not a bake directory)" % a.bake)
    _int_range("--photons", a.photons, 1000, 10 ** 8)
    if shutil.which(a.skinbake) is None:
        raise UsageError("--skinbake %s: not an executable program" % a.skinbake)
    if os.path.exists(a.out):
        raise UsageError("--out %s exists (give a new directory)" % a.out)
    from . import transfit
    try:
        transfit.fit(a.bake, a.out, a.skinbake, a.photons,
                     log=lambda t: sys.stderr.write("skinbake_mitsuba fit: %s\n" % t))
    except ValueError as e:
        shutil.rmtree(a.out, ignore_errors=True)
        raise UsageError(str(e)) from None
    except BaseException:
        shutil.rmtree(a.out, ignore_errors=True)
        raise
    return 0


def main(argv):
    parser = _Parser(prog="python -m skinbake_mitsuba",
                     description="Mitsuba 3 renders for skinbake: volumetric ground truth and table BSDF")
    sub = parser.add_subparsers(dest="command")
    _slab_parser(sub)
    _sphere_parser(sub)
    _render_parser(sub)
    _fit_parser(sub)
    try:
        a = parser.parse_args(argv)
        if a.command is None:
            parser.print_help(sys.stderr)
            return USAGE_ERROR
        cmds = {"slab": cmd_slab, "sphere": cmd_sphere, "render": cmd_render, "fit": cmd_fit}
        return cmds[a.command](a)
    except UsageError as e:
        sys.stderr.write("skinbake_mitsuba: %s\n" % e)
        return USAGE_ERROR
