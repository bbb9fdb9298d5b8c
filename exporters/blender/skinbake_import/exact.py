"""The exact mode's material: the general shader mixed with a Diffuse BSDF of colour pi * f_r
read from brdf_lut.exr at the lamp that the view layer names (layers.py makes the layers)."""
import math

import bpy

from .common import VL_DIR, VL_EXACT, VL_POINT, VL_POS
from .detail import detail_normal
from .general import general_shader
from .imageset import load_family_image, load_image
from .nodes import Tree, stamp


def _lut_sample(tr, img, nc, nphi, cl, cv, dphi, x0, y0, row_off=0.0, nrows=None):
    """pi f_r from the atlas at cos_light, cos_view in [0, 1] and dphi in [0, pi]: bilinear in the
    two neighbouring delta_phi tiles, then linear between them (blender_lut_sample in C).
    ROW_OFF (a number or a socket) and NROWS place the atlas in a taller image: its bottom row is
    row ROW_OFF of NROWS counted from the bottom (a family's stacked atlases).

    Eight texel fetches with Closest interpolation at texel centres, blended here: no GPU
    filtering and no mip-mapping, so EEVEE shows no seams where the tiles meet (its Linear
    textures pick a coarse mip level where the tile index jumps between neighbouring pixels)."""
    width = nc * nphi
    sc = tr.math("MULTIPLY", dphi, (nphi - 1) / math.pi, loc=(x0, y0 + 300))
    s0 = tr.math("MINIMUM", tr.math("FLOOR", sc, loc=(x0 + 150, y0 + 350)), nphi - 2, loc=(x0 + 300, y0 + 350))
    t = tr.math("SUBTRACT", sc, s0, loc=(x0 + 450, y0 + 300))
    x = tr.math("MULTIPLY", cv, nc - 1, loc=(x0, y0 + 100))
    j0 = tr.math("MINIMUM", tr.math("FLOOR", x, loc=(x0 + 150, y0 + 150)), nc - 2, loc=(x0 + 300, y0 + 150))
    tx = tr.math("SUBTRACT", x, j0, loc=(x0 + 450, y0 + 100))
    y = tr.math("MULTIPLY", cl, nc - 1, loc=(x0, y0 - 100))
    i0 = tr.math("MINIMUM", tr.math("FLOOR", y, loc=(x0 + 150, y0 - 50)), nc - 2, loc=(x0 + 300, y0 - 50))
    ty = tr.math("SUBTRACT", y, i0, loc=(x0 + 450, y0 - 100))
    # u of texel (tile s0, column j0) and v of row i0 (v = 0 is the bottom row, cos_light = 0).
    u00 = tr.math("DIVIDE", tr.math("ADD", tr.math("MULTIPLY_ADD", s0, nc, 0.5, loc=(x0 + 600, y0 + 250)), j0,
                                    loc=(x0 + 750, y0 + 250)), width, loc=(x0 + 900, y0 + 250))
    nrows = nrows or nc
    v00 = tr.math("DIVIDE", tr.math("ADD", tr.math("ADD", i0, 0.5, loc=(x0 + 450, y0 - 50)), row_off,
                                    loc=(x0 + 600, y0 - 50)), nrows, loc=(x0 + 750, y0 - 50))
    tiles = []
    for ds in (0, 1):
        rows = []
        for di in (0, 1):
            cols = []
            for dj in (0, 1):
                k = 4 * ds + 2 * di + dj
                u = tr.math("ADD", u00, (ds * nc + dj) / width, loc=(x0 + 1050, y0 + 400 - 150 * k))
                v = tr.math("ADD", v00, di / nrows, loc=(x0 + 1050, y0 + 330 - 150 * k))
                te = tr.tex(img, tr.xyz(u, v, 0.0, (x0 + 1200, y0 + 400 - 150 * k)), (x0 + 1350, y0 + 400 - 150 * k),
                            "EXTEND", f"brdf_lut.exr {'s0+1' if ds else 's0'} i{'+1' if di else ''} j{'+1' if dj else ''}",
                            interpolation="Closest")
                cols.append(te.outputs["Color"])
            rows.append(tr.mix(cols[0], cols[1], tx, (x0 + 1650, y0 + 350 - 300 * (2 * ds + di))))
        tiles.append(tr.mix(rows[0], rows[1], ty, (x0 + 1850, y0 + 200 - 600 * ds)))
    return tr.mix(tiles[0], tiles[1], t, (x0 + 2050, y0 - 100))



def family_corners(tr, m, x0=-900, y0=-1200):
    """The texel's place in the family's sub-grid (family_coord.exr, per axis in R, G, B): the
    slice index of each of its 2^k neighbouring sub-grid points (a socket or a number, ordered
    by corner bits, the first varying axis lowest), and a function that blends one value per
    corner (sockets of colours, in that order) multilinearly at the texel's position."""
    fam = m["family"]
    counts = fam["sub_counts"]
    uv = tr.node("ShaderNodeTexCoord", (x0, y0)).outputs["UV"]
    coord = tr.tex(load_family_image(m, "family_coord"), uv, (x0 + 200, y0), "EXTEND", "family_coord.exr",
                   interpolation="Closest")
    sep = tr.node("ShaderNodeSeparateColor", (x0 + 450, y0))
    tr.link(coord.outputs["Color"], sep.inputs["Color"])
    axes = [a for a in range(3) if counts[a] > 1]
    stride = [1, counts[0], counts[0] * counts[1]]
    base, frac = 0.0, {}
    for k, a in enumerate(axes):
        p = sep.outputs[a]
        i0 = tr.math("MINIMUM", tr.math("FLOOR", p, loc=(x0 + 650, y0 + 100 - 150 * k)), counts[a] - 2,
                     loc=(x0 + 800, y0 + 100 - 150 * k))
        frac[a] = tr.math("SUBTRACT", p, i0, loc=(x0 + 950, y0 + 100 - 150 * k))
        base = tr.math("MULTIPLY_ADD", i0, stride[a], base, loc=(x0 + 1100, y0 + 100 - 150 * k))
    slices = []
    for corner in range(1 << len(axes)):
        s = base
        if corner:
            s = tr.math("ADD", base, sum(stride[a] for k, a in enumerate(axes) if corner >> k & 1),
                        loc=(x0 + 1250, y0 + 100 - 150 * corner))
        slices.append(s)

    def blend(cols, bx=3000, by=-1500):
        # Axis by axis: the list is ordered by corner bits, lowest bit (the first axis) first.
        for k, a in enumerate(axes):
            cols = [tr.mix(cols[2 * j], cols[2 * j + 1], frac[a], (bx + 200 * k, by - 300 * j))
                    for j in range(len(cols) // 2)]
        return cols[0]
    return slices, blend


def _family_lut_sample(tr, m, nc, nphi, cl, cv, dphi):
    """pi f_r of the texel's parameters: the stacked atlases of the family's sub-grid
    (family_lut.exr), each read as _lut_sample reads brdf_lut.exr, blended multilinearly at
    the texel's sub-grid position (family_corners)."""
    img = load_family_image(m, "family_lut")
    if hasattr(img, "use_half_precision"):
        img.use_half_precision = False
    slices, blend = family_corners(tr, m)
    nrows = nc * m["family"]["slices"]
    cols = []
    for corner, s in enumerate(slices):
        row_off = tr.math("MULTIPLY", s, nc, loc=(500, -1100 - 150 * corner))
        cols.append(_lut_sample(tr, img, nc, nphi, cl, cv, dphi, -450, -2000 - 1400 * corner, row_off, nrows))
    return blend(cols, 2100, -1500)


def build_exact(m, name="skinbake exact", no_detail=False, no_specular=False, unit_scale=1.0,
                calibrate=True):
    """Mix of the general shader and a Diffuse BSDF of colour pi * f_r: the view-layer property
    skinbake_exact (0 when missing) picks the exact part in the per-lamp layers that
    setup_exact_layers makes; there skinbake_light_dir / _pos / _point give the lamp."""
    lutimg = load_image(m, "brdf_lut")
    if hasattr(lutimg, "use_half_precision"):
        lutimg.use_half_precision = False                        # EEVEE: full float texture
    nc, nphi = m["brdf_lut"]["cos_nodes"], m["brdf_lut"]["phi_nodes"]
    mat = bpy.data.materials.new(name)
    tr = Tree(mat)
    out = tr.node("ShaderNodeOutputMaterial", (2400, 0))
    geo = tr.node("ShaderNodeNewGeometry", (-2300, 300))
    nrm, area = detail_normal(tr, m, no_detail, geo)
    N = nrm if nrm is not None else geo.outputs["Normal"]
    I = geo.outputs["Incoming"]                                   # unit vector toward the viewer
    fexact = tr.attr("VIEW_LAYER", VL_EXACT, (-2300, 0), "1 in a per-lamp layer").outputs["Fac"]
    ldir = tr.attr("VIEW_LAYER", VL_DIR, (-2300, -150), "toward the sun").outputs["Vector"]
    lpos = tr.attr("VIEW_LAYER", VL_POS, (-2300, -300), "lamp position").outputs["Vector"]
    lpt = tr.attr("VIEW_LAYER", VL_POINT, (-2300, -450), "1 for point and spot").outputs["Fac"]
    topos = tr.vmath("SCALE", tr.vmath("SUBTRACT", lpos, geo.outputs["Position"], loc=(-2100, -300)),
                     loc=(-1950, -300), scale=lpt)
    L = tr.vmath("NORMALIZE", tr.vmath("ADD", ldir, topos, loc=(-1800, -200)), loc=(-1650, -200))
    L.node.label = "L: toward the lamp"
    cv_raw = tr.vmath("DOT_PRODUCT", N, I, (-1500, 400))
    cl_raw = tr.vmath("DOT_PRODUCT", N, L, (-1500, 0))
    cv = tr.math("ADD", cv_raw, 0.0, loc=(-1300, 400), clamp=True)   # clamp to [0, 1]
    cl = tr.math("ADD", cl_raw, 0.0, loc=(-1300, 0), clamp=True)
    # delta_phi: angle between the tangent-plane projections of I and L (0 = back toward the
    # lamp).  A zero projection (view or light along N) gives 90 deg, where f_r has no azimuth.
    vp = tr.vmath("NORMALIZE", tr.vmath("SUBTRACT", I, tr.vmath("SCALE", N, loc=(-1500, 250), scale=cv_raw),
                                       loc=(-1350, 250)), loc=(-1200, 250))
    lp = tr.vmath("NORMALIZE", tr.vmath("SUBTRACT", L, tr.vmath("SCALE", N, loc=(-1500, 150), scale=cl_raw),
                                       loc=(-1350, 150)), loc=(-1200, 150))
    dphi = tr.math("ARCCOSINE", tr.math("MINIMUM", tr.math("MAXIMUM", tr.vmath("DOT_PRODUCT", vp, lp, (-1050, 200)),
                                                           -1.0, loc=(-900, 200)), 1.0, loc=(-750, 200)),
                   loc=(-600, 200))
    if "family" in m:
        col = _family_lut_sample(tr, m, nc, nphi, cl, cv, dphi)
    else:
        col = _lut_sample(tr, lutimg, nc, nphi, cl, cv, dphi, -450, 0)
    if area is not None:
        col = tr.vmath("SCALE", col, loc=(1800, 0), scale=area)
    dif = tr.node("ShaderNodeBsdfDiffuse", (2000, 0))
    tr.link(col, dif.inputs["Color"])
    if nrm is not None:
        tr.link(nrm, dif.inputs["Normal"])
    gen = general_shader(tr, m, nrm, area, geo, unit_scale, no_specular, calibrate)
    mix = tr.node("ShaderNodeMixShader", (2200, 0), "general (world, area lamps) | exact (one lamp)")
    tr.link(fexact, mix.inputs["Fac"])
    tr.link(gen, mix.inputs[1])
    tr.link(dif.outputs["BSDF"], mix.inputs[2])
    tr.link(mix.outputs["Shader"], out.inputs["Surface"])
    stamp(mat, m, "exact")
    return mat
