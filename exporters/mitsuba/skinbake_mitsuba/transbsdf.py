"""The translucent mode's surface ("skinbake_translucent"), one colour channel at
a time (mono variants, as the volumetric mode).

Seen from outside:
  reflection    the bake's table minus the fitted medium's own BRDF (both
                resampled as tablebsdf.py does, the difference clipped at 0),
                plus the bake's GGX specular: the remainder;
  transmission  a rough dielectric (GGX, the bake's alpha, index n of the fit)
                into the medium; its reflection lobe is left out, the bake's
                specular stands for it.
Seen from inside: the whole rough dielectric (reflection, total internal
reflection and transmission out).
So on a flat surface under a distant light the medium returns its own BRDF and
the remainder adds the rest of the bake's: the bake's BRDF wherever the
remainder is not clipped (transfit.py, tests/mitsuba_translucent.sh).

Grazing weights: the medium under the rough top returns far more light at
grazing angles than the bake's layers under their smooth top (red, paper: 1.9
times at light 0, view 84 deg; 2.7 at 80, 80), so the remainder would be
clipped there and the surface too bright. The medium's BRDF is nearly separable
in that excess, so the dielectric's transmission across the surface, either
way, is multiplied by c(theta) of its outside direction, c = min(1,
sqrt(bake / medium)) of the azimuthal means on the diagonal theta_i = theta_o
(exit_weights): the medium's BRDF becomes c(theta_i) c(theta_o) times its own
(exactly: entry and exit each pass the surface once), which is at most the
bake's up to the separability's error, and the remainder is the bake's minus
that. The weights only take light away (the interface absorbs what it would
send beyond the bake), reciprocally.

Parameters: bake, fit (the directory transfit.fit wrote), channel (0, 1, 2),
specular (default true; false leaves the bake's GGX lobe out, for profiles).
Sampling from outside: the remainder cosine-weighted with probability P_TABLE,
else the dielectric's transmission; directions the dielectric would reflect are
never drawn there, so each branch's density is its own (pdf() says the same).
"""
import os

import drjit as dr
import mitsuba as mi
import numpy as np

from . import json_load
from . import tablebsdf
from . import tablegrid

P_TABLE = 0.5


def _az_mean(g):
    """Azimuthal mean over the grid's delta_phi axis (the last; trapezoids)."""
    ph = tablegrid.grid_phi()
    return (0.5 * (g[..., 1:] + g[..., :-1]) * np.diff(ph)).sum(axis=-1) / (ph[-1] - ph[0])


def exit_weights(bake_grid, medium_grid):
    """The grazing weights c [N_THETA] on tablegrid.grid_theta() (see the module's
    text): min(1, sqrt(bake / medium)) of the azimuthal means at theta_i =
    theta_o; at 90 deg the value at the node before (the bake's is 0 there under
    a smooth top; a rough top's medium keeps a finite value, docs/grazing.md)."""
    b = np.diagonal(_az_mean(bake_grid)).astype(np.float64)
    m = np.diagonal(_az_mean(medium_grid)).astype(np.float64)
    c = np.ones_like(b)
    ok = m > 0.0
    c[ok] = np.minimum(1.0, np.sqrt(np.maximum(b[ok], 0.0) / m[ok]))
    c[-1] = c[-2]
    return c


def remainder_grid(bake, medium_bake, k, weights=True):
    """(remainder [N_THETA][N_THETA][N_PHI], bake grid, medium grid as the
    surface passes it, grazing weights c [N_THETA]) at the wavelength index k of
    both bakes; weights=False: c = 1 (the medium as it is)."""
    grids = []
    for d in (bake, medium_bake):
        with open(os.path.join(d, "manifest.json")) as f:
            man = json_load(f)
        _, planes = tablebsdf._load_planes(os.path.join(d, "brdf.exr"), "fr.")
        grids.append(tablegrid.resample(man, planes)[k])
    c = exit_weights(grids[0], grids[1]) if weights else np.ones(tablegrid.N_THETA)
    med = grids[1] * c[:, None, None] * c[None, :, None]
    return np.maximum(grids[0] - med, 0.0), grids[0], med, c


def medium_exit_factor(medium_grid_raw, c):
    """The share of the medium's light at normal incidence that the weights c let
    out: its albedo's integrand over theta_o weighted by c(theta_o), over the
    unweighted one (c(0) = 1 enters)."""
    gt = tablegrid.grid_theta()
    row = _az_mean(medium_grid_raw[0]) * np.cos(gt) * np.sin(gt)
    trap = lambda y: float((0.5 * (y[1:] + y[:-1]) * np.diff(gt)).sum())
    return c[0] * trap(row * c) / trap(row)


class TranslucentBSDF(tablebsdf.TableBSDF):
    def __init__(self, props):
        mi.BSDF.__init__(self, props)
        bake = props["bake"]
        fitdir = props["fit"]
        c = int(props["channel"])
        with open(os.path.join(bake, "manifest.json")) as f:
            man = json_load(f)
        with open(os.path.join(fitdir, "fit.json")) as f:
            fit = json_load(f)
        k = int(fit["chan_wl"][c])
        self.wl = list(man["wavelengths_nm"])
        self.alpha = float(man["specular"]["alpha"])
        stacks = [tuple(s) for s in man["specular"]["stack_n"]]
        self.stacks = sorted(set(stacks))
        self.stack_of_wl = [self.stacks.index(s) for s in stacks]
        rem, _, _, cw = remainder_grid(bake, os.path.join(fitdir, fit["medium_bake"]), k)
        self.cw = mi.Float(cw.astype(np.float32))
        self.mode = "mono"
        self.mono_wl = k
        self.npx = tablegrid.N_THETA * tablegrid.N_THETA * tablegrid.N_PHI
        self.n_planes = 1
        self.data = mi.Float(rem.astype(np.float32).ravel())
        self.rough = mi.load_dict({"type": "roughdielectric", "distribution": "ggx",
                                   "alpha": self.alpha, "int_ior": float(fit["n"]),
                                   "ext_ior": 1.0})
        self.eta = float(fit["n"])
        # specular = false: the remainder without the bake's GGX lobe (profile measurements)
        self.with_specular = bool(props.get("specular", True))
        F = mi.BSDFFlags
        self.m_flags = (F.DiffuseReflection | F.GlossyReflection | F.GlossyTransmission
                        | F.FrontSide | F.BackSide | F.NonSymmetric)
        self.m_components = [F.DiffuseReflection | F.FrontSide,
                             F.GlossyTransmission | F.FrontSide | F.BackSide]

    def _f(self, si, wo):
        if self.with_specular:
            return tablebsdf.TableBSDF._f(self, si, wo)
        ti, to, ph = self._angles(si.wi, wo)
        return mi.Spectrum(self._diffuse_planes(ti, to, ph, [0])[0])

    @staticmethod
    def _trans_ctx(ctx):
        t = mi.BSDFContext(ctx.mode)
        t.type_mask = +mi.BSDFFlags.GlossyTransmission
        return t

    def _c(self, cos_out):
        """The grazing weight c(theta) of an outside direction's cosine (linear on
        tablegrid's nodes, uniform in u = acos(1 - 4 theta / pi))."""
        nt = tablegrid.N_THETA
        th = dr.acos(dr.clip(dr.abs(cos_out), 0.0, 1.0))
        i0, t = tablebsdf._cell(dr.acos(dr.clip(1.0 - 4.0 * th / dr.pi, -1.0, 1.0)) * ((nt - 1) / dr.pi), nt)
        return (1.0 - t) * dr.gather(mi.Float, self.cw, i0) + t * dr.gather(mi.Float, self.cw, i0 + 1)

    def eval(self, ctx, si, wo, active=True):
        ci = mi.Frame3f.cos_theta(si.wi)
        co = mi.Frame3f.cos_theta(wo)
        out = ci > 0.0
        table = self._f(si, wo) * dr.maximum(co, 0.0)
        # across the surface: the grazing weight of the outside direction
        trans = self.rough.eval(self._trans_ctx(ctx), si, wo, active & out & (co < 0.0)) * self._c(ci)
        inside = self.rough.eval(ctx, si, wo, active & ~out) * dr.select(co > 0.0, self._c(co), 1.0)
        v = dr.select(out, dr.select(co > 0.0, table, trans), inside)
        return dr.select(active, v, 0.0)

    def pdf(self, ctx, si, wo, active=True):
        ci = mi.Frame3f.cos_theta(si.wi)
        co = mi.Frame3f.cos_theta(wo)
        out = ci > 0.0
        p_table = P_TABLE * mi.warp.square_to_cosine_hemisphere_pdf(wo)
        p_trans = (1.0 - P_TABLE) * self.rough.pdf(self._trans_ctx(ctx), si, wo,
                                                   active & out & (co < 0.0))
        p_in = self.rough.pdf(ctx, si, wo, active & ~out)
        v = dr.select(out, dr.select(co > 0.0, p_table, p_trans), p_in)
        return dr.select(active, v, 0.0)

    def eval_pdf(self, ctx, si, wo, active=True):
        return self.eval(ctx, si, wo, active), self.pdf(ctx, si, wo, active)

    def sample(self, ctx, si, sample1, sample2, active=True):
        ci = mi.Frame3f.cos_theta(si.wi)
        out = ci > 0.0
        pick_table = out & (sample1 < P_TABLE)
        # the dielectric: from outside its transmission only (sample1 rescaled)
        s1 = dr.select(out, (sample1 - P_TABLE) / (1.0 - P_TABLE), sample1)
        s1 = dr.clip(s1, 0.0, 0.99999994)
        bs_o, w_o = self.rough.sample(self._trans_ctx(ctx), si, s1, sample2,
                                      active & out & ~pick_table)
        bs, w = self.rough.sample(ctx, si, s1, sample2, active & ~out)
        bs.wo = dr.select(out, bs_o.wo, bs.wo)
        bs.pdf = dr.select(out, bs_o.pdf, bs.pdf)
        bs.eta = dr.select(out, bs_o.eta, bs.eta)
        bs.sampled_type = dr.select(out, bs_o.sampled_type, bs.sampled_type)
        w = dr.select(out, w_o * self._c(ci),
                      w * dr.select(mi.Frame3f.cos_theta(bs.wo) > 0.0, self._c(mi.Frame3f.cos_theta(bs.wo)), 1.0))
        wt = mi.warp.square_to_cosine_hemisphere(sample2)
        table = self._f(si, wt) * dr.pi / P_TABLE
        bs.wo = dr.select(pick_table, wt, bs.wo)
        bs.pdf = dr.select(pick_table, P_TABLE * mi.warp.square_to_cosine_hemisphere_pdf(wt),
                           dr.select(out, (1.0 - P_TABLE) * bs.pdf, bs.pdf))
        bs.eta = dr.select(pick_table, 1.0, bs.eta)
        bs.sampled_type = dr.select(pick_table, mi.UInt32(+mi.BSDFFlags.DiffuseReflection),
                                    bs.sampled_type)
        bs.sampled_component = dr.select(pick_table, mi.UInt32(0), mi.UInt32(1))
        w = dr.select(pick_table, table, dr.select(out, w / (1.0 - P_TABLE), w))
        return bs, dr.select(active & (bs.pdf > 0.0), w, 0.0)

    def to_string(self):
        return "TranslucentBSDF[wavelength %g nm]" % self.wl[self.mono_wl]


def register():
    mi.register_bsdf("skinbake_translucent", lambda props: TranslucentBSDF(props))
