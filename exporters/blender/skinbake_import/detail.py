"""The detail normal map (pores and furrows) tiled at its physical size on each object."""
from .common import UV_SIZE_PROP
from .imageset import load_image


def detail_normal(tr, m, no_detail, geo):
    """(normal, area) sockets from normal.png tiled at its physical size, or (None, None).

    The tiling is per object: tiles per UV unit = object["skinbake_uv_size"] [m] / tile size,
    read with an Attribute node, so one material serves meshes of any UV scale.  normal.png
    holds the slopes of the physical heights, so strength 1 at the true tile size is physical.
    area = 1 / (n . N_smooth), the micro-surface area per unit of macro surface: a normal map
    alone loses the light that falls on the extra area of tilted facets (a Lambert surface under
    the face maps, mean n_z 0.87, rendered 13 % dark); with it the mean irradiance is exact."""
    d = m["detail"]
    if no_detail or d.get("flat") or not d.get("tile_mm"):
        return None, None
    img = load_image(m, "normal")
    uv = tr.node("ShaderNodeTexCoord", (-2300, -700))
    a = tr.attr("OBJECT", UV_SIZE_PROP, (-2300, -900), "metres per UV unit (object property)")
    unset = tr.math("COMPARE", a.outputs["Fac"], 0.0, 1e-12, loc=(-2100, -950))
    size = tr.math("MULTIPLY_ADD", unset, 0.1, a.outputs["Fac"], loc=(-1950, -900))   # 0.1 m if unset
    rep = tr.math("MULTIPLY", size, 1000.0 / float(d["tile_mm"]), loc=(-1800, -900))
    rep.node.label = f"tiles per UV unit (tile {float(d['tile_mm']):g} mm)"
    co = tr.vmath("MULTIPLY", uv.outputs["UV"], tr.xyz(rep, rep, 1.0, (-1650, -900)), loc=(-1500, -750))
    t = tr.tex(img, co, (-1300, -700), label="normal.png (OpenGL +Y)")
    nm = tr.node("ShaderNodeNormalMap", (-1000, -700), space="TANGENT")
    tr.link(t.outputs["Color"], nm.inputs["Color"])
    nz = tr.math("MAXIMUM", tr.vmath("DOT_PRODUCT", nm.outputs["Normal"], geo.outputs["Normal"], (-800, -850)),
                 0.2, loc=(-650, -850))
    area = tr.math("DIVIDE", 1.0, nz, loc=(-500, -850))
    area.node.label = "micro-surface area 1 / n_z"
    return nm.outputs["Normal"], area
