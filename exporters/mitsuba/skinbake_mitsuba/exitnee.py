"""Mitsuba's volumetric path tracer with next-event estimation through the rough
skin surface ("skinbake_volpath"), for the volumetric reference on the head.

Why: in volpath, light from a point light reaches the media only at the path's
hits of the rough top from inside, where the surface's GGX transmission toward
the light is evaluated for the direction the walk happened to arrive in. The
lobe covers a few per cent of those directions, so one sample is about 5 times
its mean in standard deviation and the 512-spp head was still speckled (two
seeds 12 CIEDE2000 apart, median).

What changes: at every scattering vertex x in a medium the light is estimated
through the surface: a direction d is drawn from x, half the time from the
surface's transmission lobe for the light (a GGX normal h around the normal
where the straight line from x toward the light meets the surface, the light's
direction refracted through h; Walter et al. 2007, eqs. 33-34 and 17 for the
pdf) and half the time from the phase function (so every direction is drawn,
and the weight phase x lobe / pdf stays bounded); the ray from x along d goes
through index-matched (null) boundaries, with the media's transmittance, to the
first solid surface y, where the surface's BSDF toward the light (visibility
tested) is evaluated. Its expectation over d is the light that leaves x, flies
to the surface unscattered and leaves toward the light: the term the old hit
of the top from inside estimated, so that estimate is switched off (hits of the
surface from outside keep it: the specular reflection). Paths that reach the
top from inside after a surface reflection without scattering in between (the
only ones no medium vertex accounts for) cross the dermis first, so their share
is below exp(-mu_t 2.5 mm) (nothing).

The loop itself is Mitsuba's prbvolpath (Python, in mitsuba.ad.integrators),
subclassed: only its emitter sampling is replaced. Properties: those of
prbvolpath, plus alpha (GGX alpha of the top) and eta (its inner index).
"""
import drjit as dr
import mitsuba as mi

LOBE_SHARE = 0.8    # directions from the lobe; the rest from the phase function
RR_TAU = 3.0        # optical depth below which the estimate is always made
RR_FAR = 0.25       # its probability where the line toward the light finds no top


def _ggx_pdf_refract(alpha, eta, l_loc, u_loc):
    """Density (solid angle) of the inner direction u_loc (pointing into the
    medium, z < 0) when a GGX normal h ~ D(h) h.z refracts the outer direction
    l_loc (z > 0) from index 1 into eta (Walter et al. 2007, eq. 17)."""
    h = -(l_loc + eta * u_loc)
    h = dr.normalize(dr.select(h.z < 0.0, -h, h))
    lh = dr.dot(l_loc, h)
    uh = dr.dot(u_loc, h)
    md = mi.MicrofacetDistribution(mi.MicrofacetType.GGX, alpha, False)
    d = md.eval(h)
    den = lh + eta * uh
    ok = (lh > 0.0) & (uh < 0.0) & (u_loc.z < 0.0) & (dr.abs(den) > 1e-12)
    return dr.select(ok, d * h.z * eta * eta * dr.abs(uh) / (den * den), 0.0)


class ExitNEEVolpath(mi.ad.integrators.prbvolpath.PRBVolpathIntegrator):
    def __init__(self, props):
        super().__init__(props)
        self.alpha = props.get("alpha", 0.25)
        self.eta = props.get("eta", 1.4)

    @dr.syntax
    def _first_solid(self, scene, ray, medium, channel, active):
        """(si, transmittance, distance, ok): the first non-null surface along
        ray, the media's transmittance on the way (homogeneous media)."""
        tr = mi.Spectrum(1.0)
        dist = mi.Float(0.0)
        med = mi.MediumPtr(medium)
        act = active & True
        si = dr.zeros(mi.SurfaceInteraction3f)
        solid = mi.Bool(False)
        ray = mi.Ray3f(ray)
        k = mi.UInt32(0)
        while act:
            si = scene.ray_intersect(ray, act)
            in_med = act & (med != None) & si.is_valid()
            mei = med.sample_interaction(ray, mi.Float(0.5), channel, in_med)
            mei.t = dr.select(in_med, si.t, dr.inf)
            seg = med.transmittance_eval_pdf(mei, si, in_med)[0]
            tr[in_med] *= seg
            dist[act & si.is_valid()] += si.t
            is_null = si.is_valid() & mi.has_flag(si.bsdf(ray).flags(), mi.BSDFFlags.Null)
            solid |= act & si.is_valid() & ~is_null
            through = act & is_null
            med[through & si.is_medium_transition()] = si.target_medium(ray.d)
            ray[through] = si.spawn_ray(ray.d)
            k += 1
            act = through & (k < 16)
        return si, tr, dist, solid & active

    def sample_emitter(self, mei, si, active_medium, active_surface, scene, sampler, medium,
                       channel, active, adj_emitted=None, δL=None, mode=None):
        # Surface vertices: the base class, but not for hits from inside.
        outside = active_surface & (mi.Frame3f.cos_theta(si.wi) > 0.0)
        em_s, ds_s = super().sample_emitter(mei, si, mi.Bool(False), outside, scene, sampler,
                                            medium, channel, outside, adj_emitted, δL, mode)
        am = active_medium & True    # a new mask: &= below must not change the caller's
        # The light seen from x, and the surface normal toward it.
        u_light = sampler.next_2d(am)
        ds_x, _ = scene.sample_emitter_direction(mei, u_light, False, am)
        wl = ds_x.d
        yg, _, dg, okg = self._first_solid(scene, mei.spawn_ray(wl), medium, channel, am)
        okg = okg & (dr.dot(yg.sh_frame.n, wl) > 0.0)
        ng = dr.select(okg, yg.sh_frame.n, wl)
        # Russian roulette by depth: tau, the optical depth of x under the
        # surface toward the light; deeper vertices send exp(-tau) or less.
        sig = mei.sigma_t[0] if dr.size_v(mi.Spectrum) == 1 else dr.max(mei.sigma_t)
        tau = dr.select(okg, dg * dr.dot(yg.sh_frame.n, wl) * sig, 0.0)
        q = dr.clip(dr.exp(-0.5 * (tau - RR_TAU)), 1e-4, 1.0)
        q = dr.select(okg & dr.isfinite(q), q, RR_FAR)
        am = am & (sampler.next_1d(am) < q)
        frame = mi.Frame3f(ng)
        l_loc = frame.to_local(wl)
        # d from the refraction lobe or from the phase function.
        phase = mei.medium.phase_function()
        pctx = mi.PhaseFunctionContext(sampler)
        pick = sampler.next_1d(am)
        md = mi.MicrofacetDistribution(mi.MicrofacetType.GGX, self.alpha, False)
        h, _ = md.sample(l_loc, sampler.next_2d(am))
        e = 1.0 / self.eta
        c = dr.dot(l_loc, h)
        k2 = 1.0 - e * e * (1.0 - c * c)
        u_lobe = (e * c - dr.sqrt(dr.maximum(k2, 0.0))) * h - e * l_loc
        d_lobe = frame.to_world(-u_lobe)
        d_ph, _, _ = phase.sample(pctx, mei, sampler.next_1d(am), sampler.next_2d(am), am)
        d = dr.normalize(dr.select(pick < LOBE_SHARE, d_lobe, d_ph))
        pdf_l = _ggx_pdf_refract(self.alpha, self.eta, l_loc, frame.to_local(-d))
        pdf_p = phase.eval_pdf(pctx, mei, d, am)[1]
        pdf = LOBE_SHARE * pdf_l + (1.0 - LOBE_SHARE) * pdf_p
        am = am & ((pdf > 0.0) & ((pick >= LOBE_SHARE) | ((k2 > 0.0) & (c > 0.0))))
        # Fly to the surface; the surface's BSDF toward the light there.
        y, tr, _, ok = self._first_solid(scene, mei.spawn_ray(d), medium, channel, am)
        ds_y, em_y = scene.sample_emitter_direction(y, u_light, True, ok)
        f = y.bsdf().eval(mi.BSDFContext(), y, y.to_local(ds_y.d), ok)
        val = dr.select(ok, tr * f * em_y / (dr.maximum(pdf, 1e-30) * q), 0.0)
        ds = dr.zeros(mi.DirectionSample3f)
        # lanes without an estimate still get a finite direction (the caller evaluates the
        # phase function there)
        ds.d = dr.select(active_medium, dr.select(am, d, wl), ds_s.d)
        ds.pdf = dr.select(active_medium, 1.0, ds_s.pdf)
        ds.delta = dr.select(active_medium, True, ds_s.delta)
        return dr.select(active_medium, val, dr.select(outside, em_s, 0.0)), ds

    def to_string(self):
        return "ExitNEEVolpath[max_depth = %d, alpha = %g, eta = %g]" % (
            self.max_depth, self.alpha, self.eta)


def register():
    mi.register_integrator("skinbake_volpath", lambda props: ExitNEEVolpath(props))
