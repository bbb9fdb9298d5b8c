"""The baked table as a Mitsuba 3 BSDF ("skinbake_table"), written in Python over
Dr.Jit gathers, so it runs in every variant (llvm_* vectorised, scalar_*).

  f(wi, wo) = diffuse table + the analytic GGX surface specular (Smith masking,
              facet reflectance of the clear top stack: engine/specular.c).
              The diffuse table is eval's own function (bake/bakeinterp.c:
              series through point values, linear between bin means)
              resampled on a fine grid (tablegrid.py) and looked up trilinearly.
  spectral variants: the table's wavelength planes, linear in wavelength
              between the bake's wavelengths and clamped outside them;
  rgb variants:      brdf_rgb.exr plus the specular through rgb_from_wl;
  mono variants:     the plane nearest 550 nm.
The light direction is Mitsuba's wo (sampled or toward the emitter), the view
is si.wi; delta_phi = 0 when the view is back toward the light. Sampling is
cosine-weighted (the diffuse part carries almost all of skin's reflectance;
direct light is sampled from the emitters).

Parameters: bake (directory written by skinbake bake).
"""
import math
import os
import sys

import numpy as np

import drjit as dr
import mitsuba as mi

from . import json_load
from . import tablegrid


def _load_planes(path, prefix):
    """Planes of channels PREFIX<name>, in file order: (names, array [c][rows][cols])."""
    bmp = mi.Bitmap(path)
    st = bmp.struct_()
    names = [st[i].name for i in range(bmp.channel_count())]
    arr = np.array(bmp, dtype=np.float32)
    keep = [i for i, n in enumerate(names) if n.startswith(prefix)]
    return [names[i] for i in keep], np.stack([arr[:, :, i] for i in keep])


def _cell(x, n):
    """Cell i0 in [0, n - 2] and weight t of the grid coordinate x in [0, n - 1]."""
    i0 = mi.UInt32(dr.clip(dr.floor(x), 0, n - 2))
    return i0, dr.clip(x - mi.Float(i0), 0.0, 1.0)


def _axis(ax, x):
    """Index i0 and weight t of x on the ascending nodes ax (list), clamped at
    the ends (wavelength axis)."""
    n = len(ax)
    if n == 1:
        return mi.UInt32(0), mi.Float(0.0)
    i0 = mi.UInt32(0)
    for k in range(1, n - 1):
        i0 += dr.select(x >= ax[k], 1, 0)
    nodes = mi.Float(ax)
    a0 = dr.gather(mi.Float, nodes, i0)
    a1 = dr.gather(mi.Float, nodes, i0 + 1)
    t = dr.clip((x - a0) / (a1 - a0), 0.0, 1.0)
    return i0, t


class TableBSDF(mi.BSDF):
    def __init__(self, props):
        mi.BSDF.__init__(self, props)
        bake = props["bake"]
        with open(os.path.join(bake, "manifest.json")) as f:
            man = json_load(f)
        self.wl = list(man["wavelengths_nm"])
        self.alpha = float(man["specular"]["alpha"])
        if float(man["specular"].get("macro_slope", 0.0)) > 0.0:
            # The mm-scale relief (src/engine/macro.h) is applied where skinbake evaluates the
            # BRDF; this plugin reads brdf.exr and draws the lobe itself, without it.
            print("skinbake_mitsuba: %s has specular.macro_slope %g: the table BSDF renders the "
                  "facets' BRDF without that relief (not implemented here)"
                  % (bake, float(man["specular"]["macro_slope"])), file=sys.stderr)
        stacks = [tuple(s) for s in man["specular"]["stack_n"]]
        self.stacks = sorted(set(stacks))
        self.stack_of_wl = [self.stacks.index(s) for s in stacks]
        rgb_from_wl = np.array(man["rgb"]["rgb_from_wl"], dtype=np.float64).reshape(3, len(self.wl))
        names, planes = _load_planes(os.path.join(bake, "brdf.exr"), "fr.")
        grid = tablegrid.resample(man, planes)
        if mi.is_spectral:
            self.mode = "spectral"
        elif mi.is_rgb:
            # linear sRGB of the resampled wavelengths: eval's rgb_total is
            # the same linear map of its wavelength values
            grid = np.tensordot(rgb_from_wl, grid.astype(np.float64), axes=(1, 0)).astype(np.float32)
            self.mode = "rgb"
        else:
            k = int(np.argmin([abs(w - 550.0) for w in self.wl]))
            grid = grid[k:k + 1]
            self.mono_wl = k
            self.mode = "mono"
        self.rgb_from_wl = rgb_from_wl
        self.npx = tablegrid.N_THETA * tablegrid.N_THETA * tablegrid.N_PHI
        self.n_planes = grid.shape[0]
        self.data = mi.Float(grid.ravel())
        self.m_flags = mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide
        self.m_components = [mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide]

    # ---- the BRDF ----------------------------------------------------------
    def _angles(self, wi, wo):
        """(theta_light, theta_view, delta_phi) in radians from Mitsuba's wo
        (light) and wi (view)."""
        cl = dr.clip(mi.Frame3f.cos_theta(wo), -1.0, 1.0)
        cv = dr.clip(mi.Frame3f.cos_theta(wi), -1.0, 1.0)
        dphi = dr.abs(dr.atan2(wo.y, wo.x) - dr.atan2(wi.y, wi.x))
        dphi = dr.select(dphi > dr.pi, 2.0 * dr.pi - dphi, dphi)
        return dr.acos(cl), dr.acos(cv), dphi

    def _diffuse_planes(self, ti, to, ph, planes):
        """Trilinear value on the resampled grid (tablegrid: uniform in
        u = acos(1 - 4 theta / pi) and in delta_phi) of each plane index in
        planes (list of ints or UInt32)."""
        nt, nph = tablegrid.N_THETA, tablegrid.N_PHI
        scale = (nt - 1) / dr.pi
        a0, ta = _cell(dr.acos(dr.clip(1.0 - 4.0 * ti / dr.pi, -1.0, 1.0)) * scale, nt)
        b0, tb = _cell(dr.acos(dr.clip(1.0 - 4.0 * to / dr.pi, -1.0, 1.0)) * scale, nt)
        c0, tc = _cell(ph * ((nph - 1) / dr.pi), nph)
        corners = []
        for ia, wa in ((a0, 1.0 - ta), (a0 + 1, ta)):
            for ib, wb in ((b0, 1.0 - tb), (b0 + 1, tb)):
                for ic, wc in ((c0, 1.0 - tc), (c0 + 1, tc)):
                    corners.append(((ia * nt + ib) * nph + ic, wa * wb * wc))
        out = []
        for p in planes:
            v = mi.Float(0.0)
            for idx, w in corners:
                v += w * dr.gather(mi.Float, self.data, idx + p * self.npx)
            out.append(v)
        return out

    def _specular_stacks(self, wi, wo):
        """GGX specular [1/sr] for each distinct top stack."""
        ci = mi.Frame3f.cos_theta(wo)
        co = mi.Frame3f.cos_theta(wi)
        h = dr.normalize(wi + wo)
        ch = h.z
        cd = dr.minimum(dr.dot(wo, h), 1.0)
        a2 = self.alpha * self.alpha
        den = ch * ch * (a2 - 1.0) + 1.0
        d = a2 / (dr.pi * den * den)

        def g1(c):
            t2 = (1.0 - c * c) / (c * c)
            return 2.0 / (1.0 + dr.sqrt(1.0 + a2 * t2))
        geo = d * g1(ci) * g1(co) / (4.0 * ci * co)
        valid = (ci > 1e-9) & (co > 1e-9)
        out = []
        for ns in self.stacks:
            out.append(dr.select(valid, _stack_reflectance(ns, cd) * geo, 0.0))
        return out

    def _f(self, si, wo):
        ti, to, ph = self._angles(si.wi, wo)
        spec = self._specular_stacks(si.wi, wo)
        if self.mode == "rgb":
            diff = self._diffuse_planes(ti, to, ph, [0, 1, 2])
            sp = [sum(float(self.rgb_from_wl[c][w]) * spec[self.stack_of_wl[w]] for w in range(len(self.wl)))
                  for c in range(3)]
            return mi.Color3f(diff[0] + sp[0], diff[1] + sp[1], diff[2] + sp[2])
        if self.mode == "mono":
            diff = self._diffuse_planes(ti, to, ph, [0])
            return mi.Spectrum(diff[0] + spec[self.stack_of_wl[self.mono_wl]])
        lam = si.wavelengths
        vals = []
        for k in range(len(lam)):
            w0, t = _axis(self.wl, lam[k])
            w1 = dr.minimum(w0 + 1, len(self.wl) - 1)
            d0, d1 = self._diffuse_planes(ti, to, ph, [w0, w1])
            s = mi.Float(0.0)
            for w in range(len(self.wl)):
                weight = dr.select(w0 == w, 1.0 - t, 0.0) + dr.select(w1 == w, t, 0.0)
                s += weight * spec[self.stack_of_wl[w]]
            vals.append((1.0 - t) * d0 + t * d1 + s)
        return mi.Spectrum(vals)

    # ---- Mitsuba's BSDF interface -----------------------------------------
    def eval(self, ctx, si, wo, active=True):
        up = (mi.Frame3f.cos_theta(si.wi) > 0.0) & (mi.Frame3f.cos_theta(wo) > 0.0)
        value = self._f(si, wo) * dr.maximum(mi.Frame3f.cos_theta(wo), 0.0)
        return dr.select(active & up, value, 0.0)

    def pdf(self, ctx, si, wo, active=True):
        up = (mi.Frame3f.cos_theta(si.wi) > 0.0) & (mi.Frame3f.cos_theta(wo) > 0.0)
        return dr.select(active & up, mi.warp.square_to_cosine_hemisphere_pdf(wo), 0.0)

    def eval_pdf(self, ctx, si, wo, active=True):
        return self.eval(ctx, si, wo, active), self.pdf(ctx, si, wo, active)

    def sample(self, ctx, si, sample1, sample2, active=True):
        bs = mi.BSDFSample3f()
        bs.wo = mi.warp.square_to_cosine_hemisphere(sample2)
        bs.pdf = mi.warp.square_to_cosine_hemisphere_pdf(bs.wo)
        bs.eta = 1.0
        bs.sampled_type = mi.UInt32(+mi.BSDFFlags.DiffuseReflection)
        bs.sampled_component = mi.UInt32(0)
        up = (mi.Frame3f.cos_theta(si.wi) > 0.0) & (bs.pdf > 0.0)
        value = self._f(si, bs.wo)   # f cos / pdf with the cosine pdf: f pi
        return bs, dr.select(active & up, value * dr.pi, 0.0)

    def traverse(self, callback):
        pass

    def to_string(self):
        return "TableBSDF[%d wavelengths, %s]" % (len(self.wl), self.mode)


def _stack_reflectance(ns, cos_i):
    """Reflectance of the clear stack of indices ns (top first) at incidence
    cosine cos_i, as engine/optics.c's optics_stack_reflectance (exact Fresnel,
    multiple reflections added incoherently)."""
    r_tot = mi.Float(0.0)
    c = mi.Float(cos_i)
    tir = mi.Bool(False)
    for n1, n2 in zip(ns, ns[1:]):
        if n1 == n2:
            continue
        sin_t2 = (n1 / n2) ** 2 * dr.maximum(0.0, 1.0 - c * c)
        tir |= sin_t2 >= 1.0
        ct = dr.sqrt(dr.maximum(0.0, 1.0 - sin_t2))
        rs = (n1 * c - n2 * ct) / (n1 * c + n2 * ct)
        rp = (n1 * ct - n2 * c) / (n1 * ct + n2 * c)
        r = 0.5 * (rs * rs + rp * rp)
        r_tot = r_tot + (1.0 - r_tot) * (1.0 - r_tot) * r / (1.0 - r_tot * r)
        c = ct
    return dr.select(tir, 1.0, r_tot)


def register():
    """Make "skinbake_table" known to mi.load_dict (call after choosing a variant)."""
    mi.register_bsdf("skinbake_table", lambda props: TableBSDF(props))
