"""A layer stack (skinbake simulate's --layer) as Mitsuba shapes and media.

Units: lengths cm, coefficients 1/cm, so the scene unit is the centimetre and
Mitsuba's sigma_t is mu_a + mu_s directly. The slab is a stack of rectangles of
half-width HALF_WIDTH_CM (wide against every lateral transport length of skin),
the top at z = 0, normals +z. Each boundary is a smooth dielectric where n
changes and a null (index-matched) interface where it does not; a boundary
carries the medium above as its exterior and the medium below as its interior.
Clear layers (mu_a = mu_s = 0) have no medium. Below the last layer is a clear
half space of index n_below that never returns light: the bottom rectangle is
a black absorber when n_below equals the last layer's n (and a dielectric over a
black absorber 1e-3 cm lower otherwise), which also keeps the environment from
lighting the slab from below.
"""
import math
from dataclasses import dataclass

HALF_WIDTH_CM = 20.0
KEYS = ("d", "n", "mua", "mus", "g")


@dataclass
class Layer:
    d: float          # thickness [cm]
    n: float = 1.0    # refractive index
    mua: float = 0.0  # absorption coefficient mu_a [1/cm]
    mus: float = 0.0  # scattering coefficient mu_s [1/cm]
    g: float = 0.0    # Henyey-Greenstein anisotropy

    @property
    def clear(self):
        return self.mua == 0.0 and self.mus == 0.0


_RANGES = {"d": (0.0, math.inf, "(0, inf) cm"), "n": (1.0, 10.0, "[1, 10]"),
           "mua": (0.0, 1e8, "[0, 1e8] 1/cm"), "mus": (0.0, 1e8, "[0, 1e8] 1/cm"),
           "g": (-1.0, 1.0, "(-1, 1)")}


def _check(key, v):
    lo, hi, text = _RANGES[key]
    bad = not (lo <= v <= hi) or math.isnan(v)
    if key == "d":
        bad = not (v > 0.0)
    if key == "g":
        bad = not (-1.0 < v < 1.0)
    if bad:
        raise ValueError("--layer %s=%g is outside %s" % (key, v, text))


def parse_layer(spec):
    """'d=0.01,n=1.4,mua=50,mus=185,g=0.8' -> Layer; ValueError names the key."""
    vals = {}
    for item in spec.split(","):
        key, eq, text = item.partition("=")
        key = key.strip()
        if key not in KEYS or not eq:
            raise ValueError("--layer: unknown key '%s' in '%s' (keys: d, n, mua, mus, g)" % (key, spec))
        try:
            v = float(text)
        except ValueError:
            raise ValueError("--layer %s=%s is not a number" % (key, text)) from None
        _check(key, v)
        vals[key] = v
    for key in ("d", "mua", "mus"):
        if key not in vals:
            raise ValueError("--layer '%s': %s is required" % (spec, key))
    return Layer(**vals)


def simulate_args(layers, n_above=1.0, n_below=None):
    """The skinbake simulate arguments of the same problem."""
    args = []
    for ly in layers:
        args += ["--layer", "d=%.17g,n=%.17g,mua=%.17g,mus=%.17g,g=%.17g" % (ly.d, ly.n, ly.mua, ly.mus, ly.g)]
    args += ["--n-above", "%.17g" % n_above]
    args += ["--n-below", "%.17g" % (layers[-1].n if n_below is None else n_below)]
    return args


def fresnel(n1, n2, cos_i):
    """Unpolarised Fresnel reflectance from index n1 into n2 at incidence cosine cos_i."""
    sin_t2 = (n1 / n2) ** 2 * max(0.0, 1.0 - cos_i * cos_i)
    if sin_t2 >= 1.0:
        return 1.0
    cos_t = math.sqrt(1.0 - sin_t2)
    rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
    rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t)
    return 0.5 * (rs * rs + rp * rp)


def specular_rsp(layers, theta_deg, n_above=1.0):
    """Rsp: light reflected without scattering by the smooth boundaries above the
    first scattering layer, with the multiple reflections in clear films
    (incoherent). The same quantity skinbake simulate reports as Rsp."""
    cos_a = math.cos(math.radians(theta_deg))
    sin_a = math.sin(math.radians(theta_deg))
    n_prev = n_above
    # R, T of the part already added (from above), adding interfaces downwards.
    r_top = 0.0
    t_down = 1.0
    r_from_below = 0.0
    for ly in layers:
        cos_prev = math.sqrt(max(0.0, 1.0 - (n_above * sin_a / n_prev) ** 2))
        r = fresnel(n_prev, ly.n, cos_prev)
        # adding: R = R12 + T12 r T21 / (1 - R21 r), with T12 = T21 (no absorption)
        denom = 1.0 - r_from_below * r
        r_top = r_top + t_down * t_down * r / denom
        r_from_below = r + (1.0 - r) ** 2 * r_from_below / denom
        t_down = t_down * (1.0 - r) / denom
        n_prev = ly.n
        if not ly.clear:
            break
    return r_top


def _medium(ly):
    if ly.clear:
        return None
    mu_t = ly.mua + ly.mus
    return {"type": "homogeneous", "sigma_t": mu_t, "albedo": ly.mus / mu_t,
            "phase": {"type": "hg", "g": ly.g}}


def _rect(z, bsdf, above, below, half_width):
    import mitsuba as mi
    shape = {"type": "rectangle", "bsdf": bsdf,
             "to_world": mi.ScalarTransform4f().translate([0.0, 0.0, z]).scale([half_width, half_width, 1.0])}
    if above is not None:
        shape["exterior"] = above
    if below is not None:
        shape["interior"] = below
    return shape


def _interface(n_above, n_below):
    if n_above == n_below:
        return {"type": "null"}
    return {"type": "dielectric", "int_ior": n_below, "ext_ior": n_above}


def slab_shapes(layers, n_above=1.0, n_below=None, half_width=HALF_WIDTH_CM):
    """Scene-dict entries (name -> shape) of the slab, top at z = 0."""
    if n_below is None:
        n_below = layers[-1].n
    media = [_medium(ly) for ly in layers]
    shapes = {}
    z = 0.0
    n_prev = n_above
    above = None
    for i, ly in enumerate(layers):
        if math.isinf(ly.d):
            raise ValueError("an infinite layer cannot be a slab; give it a thickness")
        shapes["boundary_%d" % i] = _rect(z, _interface(n_prev, ly.n), above, media[i], half_width)
        z -= ly.d
        n_prev = ly.n
        above = media[i]
    black = {"type": "diffuse", "reflectance": 0.0}
    if n_below == n_prev:
        shapes["bottom"] = _rect(z, black, above, None, half_width)
    else:
        shapes["bottom"] = _rect(z, _interface(n_prev, n_below), above, None, half_width)
        shapes["absorber"] = _rect(z - 1e-3, black, None, None, half_width)
    return shapes


def max_depth(layers, weight_floor=1e-4):
    """A path depth after which every path's weight is below weight_floor: the
    scattering albedo bounds the weight at each event, so the light lost by the
    cut is below weight_floor (1e-4 of the incident power, well under the
    measurements' errors). Surface crossings count as depth in volpath, hence the
    margin. Russian roulette is not used (volpath's
    was measured biased on these slabs: Rd 0.347 against 0.3596)."""
    a = max([ly.mus / (ly.mua + ly.mus) for ly in layers if not ly.clear] + [0.0])
    if a >= 1.0:
        return 1 << 20
    if a <= 0.0:
        return 64
    n = math.log(weight_floor) / math.log(a)
    return int(min(1.25 * n + 64, 1 << 20))
