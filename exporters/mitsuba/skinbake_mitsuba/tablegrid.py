"""A bake table resampled on a fine uniform grid, for trilinear lookup in a renderer.

skinbake eval (src/bake/bakeinterp.c) does not interpolate a table linearly:
adding-doubling wavelengths (manifest table.values "points") are point values at
Chebyshev-Lobatto nodes in theta and equally spaced nodes in delta_phi, and eval
sums the series through them (a Chebyshev series in u = acos(1 - 4 theta / pi)
per theta axis, a cosine series in delta_phi; with the default incidence nodes
the grid is completed by the row theta_i = 90 deg, f(90, b) = f(b, 90) by
reciprocity (0 under a smooth top; the corner from the quadratic through the
grazing-exit column's last three nodes), and the series is made symmetric in
(theta_i, theta_o)).  Linear interpolation between those nodes
is 1 % low on a lit sphere (the BRDF is concave between nodes 10 deg apart).
Bin means ("bins", Monte Carlo) are linear between the bin centres and go to 0
at 90 deg, as in bakeinterp.c; under a rough top (the manifest's
layers[].layers[0].rough_top) the exit axis is held past its last centre and
incidence goes linearly to f(90, theta_o) = f(theta_o, 90) by reciprocity.

This module computes eval's function on a grid of STEP_DEG in every axis, so
that the renderer's trilinear lookup on it is within GRID_ERROR of eval (the
curvature term h^2 f'' / 8 at 1 deg; tests/mitsuba_table.sh checks it).
Only numpy: the plugin must not depend on the skinbake binary.
"""
import math

import numpy as np

N_THETA = 121
N_PHI = 121


def grid_theta():
    """theta [rad] of the grid: uniform in u = acos(1 - 4 theta / pi), the variable
    in which eval's series is a polynomial; it is finest at 0 and 90 deg, where
    the BRDF falls to 0 at grazing."""
    return 0.25 * math.pi * (1.0 - np.cos(np.linspace(0.0, math.pi, N_THETA)))


def grid_phi():
    return np.radians(np.linspace(0.0, 180.0, N_PHI))


def _dct1_matrix(n):
    """Values at nodes t_j = j pi / (n - 1) -> coefficients of cos(k t) (bakeinterp.c dct1)."""
    j = np.arange(n)
    m = np.cos(np.pi * np.outer(j, j) / (n - 1)) * (2.0 / (n - 1))
    m[:, 0] *= 0.5
    m[:, -1] *= 0.5
    m[0, :] *= 0.5
    m[-1, :] *= 0.5
    return m


def _dct1(v, axis):
    n = v.shape[axis]
    if n < 2:
        return v
    return np.moveaxis(np.tensordot(_dct1_matrix(n), np.moveaxis(v, axis, 0), axes=(1, 0)), 0, axis)


def _cheb_u(theta):
    return np.arccos(np.clip(1.0 - 4.0 * theta / math.pi, -1.0, 1.0))


def _cos_basis(u, n):
    return np.cos(np.outer(u, np.arange(n)))


def _square_nodes(ti, to_nodes):
    return (len(ti) == len(to_nodes) - 1 and np.allclose(ti, to_nodes[:-1], atol=1e-9)
            and abs(to_nodes[-1] - 0.5 * math.pi) < 1e-9)


def _between(w, r, ax, xv):
    """Row r of w: linear weights of xv between the two nodes of ax around it."""
    lo = int(np.searchsorted(ax, xv, side="right")) - 1
    t = (xv - ax[lo]) / (ax[lo + 1] - ax[lo])
    w[r, lo] = 1.0 - t
    w[r, lo + 1] = t


def _linear_to_zero(ax, x):
    """Weights [len(x)][len(ax)] of bakeinterp.c's axis_weights: linear between nodes,
    held below the first, from the last linear to 0 at 90 deg."""
    w = np.zeros((len(x), len(ax)))
    n = len(ax)
    for r, xv in enumerate(x):
        if xv <= ax[0] or (n == 1 and ax[0] >= 0.5 * math.pi):
            w[r, 0] = 1.0
        elif xv >= ax[-1]:
            end = 0.5 * math.pi - ax[-1]
            t = min(1.0, (xv - ax[-1]) / end) if end > 0.0 else 0.0
            w[r, -1] = 1.0 - t
        else:
            _between(w, r, ax, xv)
    return w


def _linear_held(ax, x):
    """Weights of bakeinterp.c's phi_weights: linear between nodes, held at both ends."""
    w = np.zeros((len(x), len(ax)))
    for r, xv in enumerate(x):
        if xv <= ax[0]:
            w[r, 0] = 1.0
        elif xv >= ax[-1]:
            w[r, -1] = 1.0
        else:
            _between(w, r, ax, xv)
    return w


def _grazing_row(c, t):
    """Row theta_i = 90 deg of the square grid c [n][n][p] (bakeinterp.c grazing_row)."""
    n = c.shape[0]
    c[n - 1, :n - 1] = c[:n - 1, n - 1]
    if n < 4:
        return
    x, tt = 0.5 * math.pi, t[n - 4:n - 1]
    for j in range(3):
        lj = 1.0
        for q in range(3):
            if q != j:
                lj *= (x - tt[q]) / (tt[j] - tt[q])
        c[n - 1, n - 1] += lj * c[n - 4 + j, n - 1]


def _points_grid(plane, ti, to_nodes, ph_nodes, gt, gp):
    """eval's series through one point-value plane [n_ti][n_to][n_phi], on the grid."""
    n_ti, n, p = plane.shape
    sym = _square_nodes(ti, to_nodes)
    c = np.zeros((n if sym else n_ti, n, p))
    c[:n_ti] = plane
    if sym:
        _grazing_row(c, to_nodes)
    c = _dct1(_dct1(c, 2), 1)
    if sym:
        c = _dct1(c, 0)
        c = 0.5 * (c + c.transpose(1, 0, 2))
        bi = _cos_basis(_cheb_u(gt), n)
    else:
        bi = _linear_to_zero(ti, gt)
    bo = _cos_basis(_cheb_u(gt), n)
    bp = _cos_basis(gp, p)
    return np.einsum("jkm,aj,bk,cm->abc", c, bi, bo, bp, optimize=True)


def _bins_grid(plane, ti, to_centres, ph_centres, gt, gp, rough=False):
    wi = _linear_to_zero(ti, gt)
    wo = (_linear_held if rough else _linear_to_zero)(to_centres, gt)
    wp = _linear_held(ph_centres, gp)
    g = np.einsum("jkm,aj,bk,cm->abc", plane, wi, wo, wp, optimize=True)
    if rough:
        # bakeinterp.c bins_grazing_end: past the last incidence node, linear to
        # the last exit bin's row at incidence min(theta_o, last node)
        end = 0.5 * math.pi - ti[-1]
        t = np.clip((gt - ti[-1]) / end, 0.0, 1.0) if end > 0.0 else np.zeros_like(gt)
        wl = _linear_held(ti, np.minimum(gt, ti[-1]))
        fend = np.einsum("jm,bj,cm->bc", plane[:, -1, :], wl, wp, optimize=True)
        g += t[:, None, None] * fend[None, :, :]
    return g


def rough_top(man):
    """Whether some wavelength's stack has a rough top boundary (bakeinterp.c)."""
    for lw in man.get("layers", []):
        ls = lw.get("layers", []) if isinstance(lw, dict) else []
        if ls and (ls[0].get("rough_top") or 0) > 0:
            return True
    return False


def resample(man, planes):
    """The wavelength planes of brdf.exr ([n_wl][rows][cols], rows theta_i * n_to +
    theta_o) as eval's function on the grid: [n_wl][N_THETA][N_THETA][N_PHI]."""
    ti = np.radians(man["theta_i_deg"])
    values = man.get("table", {}).get("values", [])
    gt, gp = grid_theta(), grid_phi()
    out = np.empty((planes.shape[0], N_THETA, N_THETA, N_PHI), dtype=np.float32)
    for w in range(planes.shape[0]):
        points = w < len(values) and values[w] == "points" and "theta_o_nodes_deg" in man
        to = np.radians(man["theta_o_nodes_deg" if points else "theta_o_centres_deg"])
        ph = np.radians(man["delta_phi_nodes_deg" if points else "delta_phi_centres_deg"])
        plane = planes[w].astype(np.float64).reshape(len(ti), len(to), len(ph))
        if points:
            out[w] = _points_grid(plane, ti, to, ph, gt, gp)
        else:
            out[w] = _bins_grid(plane, ti, to, ph, gt, gp, rough_top(man))
    return out
