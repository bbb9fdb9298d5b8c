"""Pixel means of a BRDF on a sphere seen by an orthographic camera under parallel
lights, from a scene.json (docs/scene-json.md, as `skinbake export` writes it): the
geometry the renderer tests need to compare a render's pixels, box-filtered over the
pixel, with a BRDF given at points (tests/mitsuba_silhouette.sh; the BRDF angles of
tests/mitsuba_table.sh).  numpy.  All in scene.json's frame (POV-Ray's, left-handed);
the angles do not depend on the frame.

    sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
    import ortho_sphere as osp
"""
import json

import numpy as np


def angles(nrm, light, view):
    """(theta_i, theta_o, delta_phi) in degrees for unit normals nrm [..., 3] and unit
    directions toward the light and the viewer (each [3] or [..., 3]); delta_phi as
    `skinbake eval` takes it: 0 with light and viewer on the same side (back toward the
    light), 180 on opposite sides (the mirror side); 0 where either is along the normal."""
    nrm = np.asarray(nrm, dtype=float)
    ci = np.clip(np.sum(nrm * light, axis=-1), -1.0, 1.0)
    co = np.clip(np.sum(nrm * view, axis=-1), -1.0, 1.0)
    lt = light - ci[..., None] * nrm
    vt = view - co[..., None] * nrm
    den = np.linalg.norm(lt, axis=-1) * np.linalg.norm(vt, axis=-1)
    cp = np.where(den > 1e-12, np.sum(lt * vt, axis=-1) / np.maximum(den, 1e-300), 1.0)
    return np.degrees(np.arccos(ci)), np.degrees(np.arccos(co)), np.degrees(np.arccos(np.clip(cp, -1.0, 1.0)))


class View:
    """The scene's orthographic camera, its one sphere and its parallel lights."""

    def __init__(self, scene_json):
        with open(scene_json) as f:
            sc = json.load(f)
        cam = sc["camera"]
        if cam["type"] != "orthographic":
            raise ValueError("%s: the camera is %s, not orthographic" % (scene_json, cam["type"]))
        self.w, self.h = sc["width_px"], sc["height_px"]
        loc, at = np.array(cam["location"], float), np.array(cam["look_at"], float)
        d = (at - loc) / np.linalg.norm(at - loc)
        right = np.cross(np.array(cam["sky"], float), d)      # left-handed: sky x dir points right
        self.right = right / np.linalg.norm(right)
        self.up = np.cross(d, self.right)
        self.toward_cam = -d
        self.centre = at
        self.px = cam["width"] / self.w                   # pixel side (square pixels)
        spheres = [o for o in sc["objects"] if o["shape"] == "sphere"]
        if len(spheres) != 1 or len(sc["objects"]) != 1:
            raise ValueError("%s: one sphere and nothing else expected" % scene_json)
        o = spheres[0]
        m = np.array(o["to_world"], float)
        self.sc = (m @ np.array(list(o["center"]) + [1.0]))[:3]
        self.radius = o["radius"] * o["scale"]
        self.lights = []
        for L in sc["lights"]:
            if L["type"] != "parallel":
                raise ValueError("%s: light '%s' is %s, not parallel" % (scene_json, L["name"], L["type"]))
            t = -np.array(L["direction"], float)
            self.lights.append((t / np.linalg.norm(t), np.array(L["irradiance_rgb"], float)))

    def point(self, col, row):
        """The image-plane offsets (x right, y up) of the continuous pixel coordinates
        (col, row): (0, 0) is the image's top-left corner, pixel (r, c) spans
        [c, c + 1] x [r, r + 1]."""
        col, row = np.asarray(col, float), np.asarray(row, float)
        return (col - 0.5 * self.w) * self.px, (0.5 * self.h - row) * self.px

    def normal(self, x, y):
        """Unit normals [..., 3] where the rays at image offsets (x, y) meet the sphere
        (NaN off it)."""
        c = self.sc - self.centre
        u = x - c @ self.right
        v = y - c @ self.up
        z2 = self.radius ** 2 - u * u - v * v
        z = np.sqrt(np.where(z2 >= 0, z2, np.nan))
        return (u[..., None] * self.right + v[..., None] * self.up + z[..., None] * self.toward_cam) / self.radius

    def ring(self, min_theta_out, margin=0.02):
        """Pixels (rows, cols) wholly on the sphere and wholly lit by every light (the
        footprint's corners, widened by margin pixels, all on the sphere and facing
        every light), whose centre's exit angle is min_theta_out deg or more."""
        r, c = np.mgrid[0:self.h, 0:self.w]
        keep = np.ones(r.shape, bool)
        for dr in (-margin, 1 + margin):
            for dc in (-margin, 1 + margin):
                n = self.normal(*self.point(c + dc, r + dr))
                ok = np.isfinite(n[..., 0])
                for l, _ in self.lights:
                    ok &= np.nan_to_num(n @ l, nan=-1.0) > 0
                keep &= ok
        n = self.normal(*self.point(c + 0.5, r + 0.5))
        to = np.degrees(np.arccos(np.clip(np.nan_to_num(n @ self.toward_cam, nan=0.0), -1, 1)))
        keep &= to >= min_theta_out
        return r[keep], c[keep]

    def quadrature(self, rows, cols, order):
        """Gauss-Legendre order x order points over each pixel's footprint: per light,
        (theta_i, theta_o, delta_phi) [n_px, order^2] in degrees, cos(theta_i) and the
        weights [order^2] (summing to 1): the pixel mean of L is sum w E cos f."""
        g, gw = np.polynomial.legendre.leggauss(order)
        g = 0.5 * (g + 1.0)
        gw = 0.5 * gw
        dc, dr = np.meshgrid(g, g)
        wts = np.outer(gw, gw).ravel()
        x, y = self.point(cols[:, None] + dc.ravel()[None, :], rows[:, None] + dr.ravel()[None, :])
        n = self.normal(x, y)
        out = []
        for l, e in self.lights:
            ti, to, ph = angles(n, l, self.toward_cam)
            out.append((ti, to, ph, np.cos(np.radians(ti)), e))
        return out, wts
