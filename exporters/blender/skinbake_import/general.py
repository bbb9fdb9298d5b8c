"""The general mode: a material for any lights and engines.  With the manifest's fit a mixture of
closures whose view-dependent weights reproduce the baked BRDF (blender_fit.h): "general_fit" on
Blender 3.x, "general_fit_v4" on 4.x and 5.x, whose subsurface colour is made by the Base Colour
that Blender's measured response turns into it (calibration.VIEW_RESPONSE); else one Principled
BSDF with random-walk subsurface."""
import math
import os

import bpy

from . import calibration
from .common import say
from .detail import cavity, detail_normal, far_area_mean, far_roughness
from .footprint import walk_radius
from .imageset import _check_fit, load_family_image, load_image
from .nodes import Tree, sock, stamp


def _set_radius(tr, bsdf, rad, loc):
    """The Principled BSDF's Subsurface Radius: RAD (RGB or a socket), kept above the radius this
    Blender renders as diffuse (footprint.walk_radius)."""
    rad = walk_radius(tr, rad, loc)
    if isinstance(rad, bpy.types.NodeSocket):
        tr.link(rad, bsdf.inputs["Subsurface Radius"])
    else:
        bsdf.inputs["Subsurface Radius"].default_value = rad


def _general_principled(tr, m, nrm, unit_scale, no_specular, calibrate, area_mean):
    """One Principled BSDF: albedo (calibrated), random-walk radius, index, roughness map."""
    bsdf = tr.node("ShaderNodeBsdfPrincipled", (200, 300))
    bsdf.subsurface_method = "RANDOM_WALK"
    uv = tr.node("ShaderNodeTexCoord", (-1500, 600))
    fam = "family" in m
    alb = tr.tex(load_family_image(m, "albedo_map") if fam else load_image(m, "albedo", data=False),
                 uv.outputs["UV"], (-600, 700), "EXTEND" if fam else "REPEAT",
                 label="albedo_map.exr (per texel)" if fam else "albedo.exr")
    base = alb.outputs["Color"]
    k = calibration.albedo_factor(m["albedo_rgb"], float(m["roughness"])) if calibrate else [1.0] * 3
    k = [x / area_mean for x in k]
    if k != [1.0] * 3:
        base = tr.vmath("MULTIPLY", base, [1.0 / x for x in k], loc=(-300, 700))
        base.node.label = "albedo / (" + ", ".join(f"{x:.4f}" for x in k) + ") calibration"
    tr.link(base, bsdf.inputs["Base Color"])
    if sock(bsdf.inputs, "Subsurface Color"):                      # 3.x only
        tr.link(base, sock(bsdf.inputs, "Subsurface Color"))
    # 3.x: "Subsurface" is the weight and multiplies the radius; 4.x: Weight and Scale.
    sock(bsdf.inputs, "Subsurface Weight", "Subsurface").default_value = 1.0
    if sock(bsdf.inputs, "Subsurface Scale"):
        sock(bsdf.inputs, "Subsurface Scale").default_value = 1.0
    rad = family_radius(tr, m, uv.outputs["UV"], unit_scale, (-600, 200)) if fam else \
        [x / unit_scale for x in m["sss_radius_m"]]
    _set_radius(tr, bsdf, rad, (-900, -100))
    n = float(m["ior"])
    bsdf.inputs["IOR"].default_value = n
    # Where the export-time fit found the bake's surface reflection negligible, leave it out too.
    if isinstance(m.get("general_fit"), dict) and not m["general_fit"].get("specular", True):
        no_specular = True
    spec = sock(bsdf.inputs, "Specular")                           # 3.x: 0.5 <-> F0 = 0.04
    if spec is not None:
        spec.default_value = 0.0 if no_specular else ((n - 1) / (n + 1)) ** 2 / 0.08
    elif sock(bsdf.inputs, "Specular IOR Level") is not None:      # 4.x: 0.5 = as the IOR says
        sock(bsdf.inputs, "Specular IOR Level").default_value = 0.0 if no_specular else 0.5
    rough = tr.tex(load_image(m, "roughness"), uv.outputs["UV"], (-600, 400), label="roughness.png")
    tr.link(far_roughness(tr, rough.outputs["Color"]), bsdf.inputs["Roughness"])
    if nrm is not None:
        tr.link(nrm, bsdf.inputs["Normal"])
    return bsdf.outputs["BSDF"]



def _ramp(tr, cos_v, nodes, values, scale, loc, label):
    """ColorRamp (linear) of RGB VALUES at positions NODES, read at cos_v; values times SCALE
    (a number per channel or a function of the value)."""
    r = tr.node("ShaderNodeValToRGB", loc, label)
    cr = r.color_ramp
    cr.interpolation = "LINEAR"
    cr.color_mode = "RGB"
    els = cr.elements
    els[0].position, els[1].position = nodes[0], nodes[-1]
    for x in nodes[1:-1]:
        els.new(x)
    for e in els:
        j = min(range(len(nodes)), key=lambda i: abs(nodes[i] - e.position))
        v = values[j]
        e.color = [scale(c, v[c]) for c in range(3)] + [1.0]
    tr.link(cos_v, r.inputs["Fac"])
    return r.outputs["Color"]


def _v4_base(f, area_mean, calibrate):
    """Blender 4+: the Base Colour per cos_view node and channel whose measured response R(base,
    cos_view) is the fit's s(v) (calibration.VIEW_RESPONSE)."""
    c = calibration.view_measurement() if calibrate else None
    if calibrate and c is None:
        say(f"Blender {bpy.app.version_string.split()[0]} has no measured subsurface response "
            "(calibration.VIEW_RESPONSE): the fit's colours are used as Base Colours, uncorrected")
    out, short = [], 0
    for cv, s in zip(f["cos_view_nodes"], f["subsurface_rgb"]):
        row = []
        for x in s:
            b, ok = calibration.base_for_response(x * area_mean, float(cv), c) if c else (x * area_mean, True)
            short += not ok
            row.append(b)
        out.append(row)
    if short:
        say(f"general mode: {short} subsurface colours of the fit are brighter than Base Colour 1 renders "
            "in this Blender: Base Colour 1 used there")
    return out


def _general_fit(tr, m, f, nrm, area, geo, unit_scale, no_specular, calibrate, area_mean):
    """The closure mixture fitted at export time (manifest general_fit on 3.x, general_fit_v4 on 4+,
    blender_fit.h)."""
    v4 = bpy.app.version >= (4, 0, 0)
    N = nrm if nrm is not None else geo.outputs["Normal"]
    cos_v = tr.math("ADD", tr.vmath("DOT_PRODUCT", N, geo.outputs["Incoming"], (-1500, 1300)), 0.0,
                    loc=(-1300, 1300), clamp=True)
    nodes = [float(x) for x in f["cos_view_nodes"]]

    def sss_scale(c, v):
        k = calibration.sss_albedo_factor(v) if calibrate else 1.0
        return v / k * area_mean
    if v4:
        col_s = _ramp(tr, cos_v, nodes, _v4_base(f, area_mean, calibrate), lambda c, v: v, (-1000, 1500),
                      "Base Colour b(cos_view): R(b, cos_view) = s(cos_view)")
    else:
        col_s = _ramp(tr, cos_v, nodes, f["subsurface_rgb"], sss_scale, (-1000, 1500),
                      "subsurface colour s(cos_view)")
    fam_uv = tr.node("ShaderNodeTexCoord", (-1500, 1900)).outputs["UV"] if "family" in m else None
    if fam_uv is not None:                   # the fit's colour scaled by the texel's albedo
        amap = tr.tex(load_family_image(m, "albedo_map"), fam_uv, (-1300, 1900), "EXTEND", "albedo_map.exr")
        ratio = tr.vmath("MULTIPLY", amap.outputs["Color"], [1.0 / max(x, 1e-6) for x in m["albedo_rgb"]],
                         loc=(-1000, 1900))
        ratio.node.label = "albedo_map / albedo (per texel)"
        col_s = tr.vmath("MULTIPLY", col_s, ratio, loc=(-800, 1700))
    col_g = _ramp(tr, cos_v, nodes, f["glossy_rgb"], lambda c, v: v, (-1000, 1100), "glossy colour g(cos_view)")
    if area is not None:
        col_g = tr.vmath("SCALE", col_g, loc=(-700, 1100), scale=area)
    sss = tr.node("ShaderNodeBsdfPrincipled", (-400, 1700),
                  "subsurface: s(v)" if v4 else "subsurface: s(v) (1 - F_L / 2)")
    sss.subsurface_method = "RANDOM_WALK"
    tr.link(col_s, sss.inputs["Base Color"])
    if sock(sss.inputs, "Subsurface Color"):
        tr.link(col_s, sock(sss.inputs, "Subsurface Color"))
    sock(sss.inputs, "Subsurface Weight", "Subsurface").default_value = 1.0
    if v4:                                   # the inputs VIEW_RESPONSE was measured with
        sock(sss.inputs, "Subsurface Scale").default_value = 1.0
        sss.inputs["IOR"].default_value = calibration.VIEW_IOR
    rad = family_radius(tr, m, fam_uv, unit_scale, (-800, 1950)) if fam_uv is not None else \
        [x / unit_scale for x in m["sss_radius_m"]]
    _set_radius(tr, sss, rad, (-1400, 2200))
    # Its retro-reflection term is in the fit; roughness 0 would give NaN pixels in EEVEE.
    sss.inputs["Roughness"].default_value = float(f.get("subsurface_roughness", 0.0))
    sock(sss.inputs, "Specular", "Specular IOR Level").default_value = 0.0
    gl = tr.node("ShaderNodeBsdfGlossy", (-400, 1100), "forward lobe g(v) f_AS", distribution="ASHIKHMIN_SHIRLEY")
    tr.link(col_g, gl.inputs["Color"])
    gl.inputs["Roughness"].default_value = float(f["glossy_roughness"])
    shader = tr.node("ShaderNodeAddShader", (-100, 1400))
    tr.link(sss.outputs["BSDF"], shader.inputs[0])
    tr.link(gl.outputs["BSDF"], shader.inputs[1])
    out = shader.outputs["Shader"]
    closures = [sss, gl]
    if not no_specular and f.get("specular", True):
        sp = tr.node("ShaderNodeBsdfPrincipled", (-400, 600), "surface specular (GGX, bake's index)",
                     distribution="GGX")
        sp.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        sock(sp.inputs, "Subsurface Weight", "Subsurface").default_value = 0.0
        n = float(f["specular_ior"])
        sp.inputs["IOR"].default_value = n
        if sock(sp.inputs, "Specular") is not None:
            sp.inputs["Specular"].default_value = ((n - 1) / (n + 1)) ** 2 / 0.08
        sp.inputs["Roughness"].default_value = math.sqrt(float(f["specular_alpha"]))
        r_far = far_roughness(tr, math.sqrt(float(f["specular_alpha"])), loc=(-700, 600))
        if not isinstance(r_far, float):
            tr.link(r_far, sp.inputs["Roughness"])
        add = tr.node("ShaderNodeAddShader", (100, 1200))
        tr.link(out, add.inputs[0])
        tr.link(sp.outputs["BSDF"], add.inputs[1])
        out = add.outputs["Shader"]
        closures.append(sp)
    if nrm is not None:       # the subsurface closures under the relief blurred by their spread
        dn = getattr(tr, "nrm_diffuse", None) or nrm
        for i, c in enumerate(closures):
            tr.link(nrm if i >= 2 else dn, c.inputs["Normal"])     # [sss, gl, surface specular]
    return out


def general_shader(tr, m, nrm, area, geo, unit_scale, no_specular, calibrate):
    """The fitted mixture when the manifest has one for this Blender, else one Principled BSDF."""
    # Subsurface light is averaged over many facets, so its micro-area correction is the mean one.
    area_mean = 1.0
    if nrm is not None and m["detail"].get("mean_normal_z"):
        area_mean = 1.0 / float(m["detail"]["mean_normal_z"])
    area_mean = far_area_mean(tr, area_mean)
    f = m.get("general_fit_v4" if bpy.app.version >= (4, 0, 0) else "general_fit")
    if isinstance(f, dict):
        if f is m.get("general_fit_v4"):
            _check_fit(f, os.path.join(m.get("_dir", "."), "manifest.json") + ": general_fit_v4")
        return _general_fit(tr, m, f, nrm, area, geo, unit_scale, no_specular, calibrate, area_mean)
    return _general_principled(tr, m, nrm, unit_scale, no_specular, calibrate, area_mean)


def build_general(m, name="skinbake general", no_detail=False, no_specular=False, unit_scale=1.0,
                  calibrate=True):
    """A material for any lights and engines (see _general_shader)."""
    mat = bpy.data.materials.new(name)
    tr = Tree(mat)
    out = tr.node("ShaderNodeOutputMaterial", (1600, 0))
    geo = tr.node("ShaderNodeNewGeometry", (-2300, 300))
    nrm, area = detail_normal(tr, m, no_detail, geo, far=True)
    shader = general_shader(tr, m, nrm, area, geo, unit_scale, no_specular, calibrate)
    tr.link(cavity(tr, m, shader), out.inputs["Surface"])
    stamp(mat, m, "general")
    return mat


def family_radius(tr, m, uv, unit_scale, loc):
    """The texel's subsurface radius (sss_radius_map.exr, metres) in scene units."""
    t = tr.tex(load_family_image(m, "sss_radius_map"), uv, loc, "EXTEND", "sss_radius_map.exr (per texel)")
    return tr.vmath("SCALE", t.outputs["Color"], loc=(loc[0] + 300, loc[1]), scale=1.0 / unit_scale)
