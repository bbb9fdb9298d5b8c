"""A unit sphere with the table BSDF under a directional light, seen by an
orthographic camera along +z: every pixel has its own (theta_i, theta_o,
delta_phi), so one image checks the whole table against skinbake eval.
Pixel (row r, column c) of an N x N image is centred on x = (c + 0.5)/N*2 - 1,
y = 1 - (r + 0.5)/N*2 (normal (x, y, sqrt(1 - x^2 - y^2))); the light's
irradiance is 1 on a surface facing it, so a pixel is f cos(theta_i)."""
import time

import numpy as np


def render(bake, light_dir, size, spp, wavelength_nm=None, variant_name=None):
    """(image [size][size] float, seconds, variant). In spectral variants the film
    sees the 1 nm band around wavelength_nm (one band per render, so no pixel
    shares its wavelengths with another band); in rgb variants the image has
    3 channels."""
    from . import variant
    kind = "spectral" if wavelength_nm is not None else "rgb"
    used = variant.choose(kind, variant_name)
    import mitsuba as mi
    from . import tablebsdf
    tablebsdf.register()
    d = np.asarray(light_dir, dtype=float)
    d = d / np.linalg.norm(d)
    # a plain value is an equal-energy spectrum in spectral variants but D65
    # white (1.21, 0.95, 0.91) in rgb variants: give rgb variants rgb(1, 1, 1)
    irradiance = {"type": "spectrum", "value": 1.0}
    if mi.is_rgb:
        irradiance = {"type": "rgb", "value": [1.0, 1.0, 1.0]}
    if wavelength_nm is not None and mi.is_spectral:
        w = float(wavelength_nm)
        film = {"type": "specfilm", "width": size, "height": size, "rfilter": {"type": "box"},
                "band": {"type": "spectrum", "value": [(w - 0.5, 1.0), (w + 0.5, 1.0)]}}
    else:
        film = {"type": "hdrfilm", "width": size, "height": size, "rfilter": {"type": "box"},
                "pixel_format": "rgb"}
    scene = {"type": "scene", "integrator": {"type": "path", "max_depth": 2},
             "sphere": {"type": "sphere", "bsdf": {"type": "skinbake_table", "bake": bake}},
             "sun": {"type": "directional", "direction": (-d).tolist(),
                     "irradiance": irradiance},
             "sensor": {"type": "orthographic",
                        "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 5], target=[0, 0, 0], up=[0, 1, 0]),
                        "film": film,
                        # stratified pixel positions: the image is a pixel mean of a
                        # function that changes fast at grazing light
                        "sampler": {"type": "stratified", "sample_count": spp}}}
    t0 = time.time()
    img = np.array(mi.render(mi.load_dict(scene)))
    return img, time.time() - t0, used
