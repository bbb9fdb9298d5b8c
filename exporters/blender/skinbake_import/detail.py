"""The detail normal map (pores and furrows) tiled at its physical size on each object, and the
relief as roughness where it is smaller than a pixel (roughness_far.png, docs/relief.md)."""
import math
import os
import struct
import zlib

import bpy

from .common import UV_SIZE_PROP
from .imageset import load_image

# Where the far roughness takes over: from a primary cell (one block of roughness_far.png) over
# FAR_NEAR_PX pixels, where the normal map still resolves it, to one over FAR_FAR_PX pixels.
FAR_NEAR_PX = 2.0
FAR_FAR_PX = 0.5


def detail_normal(tr, m, no_detail, geo, far=False):
    """(normal, area) sockets from normal.png tiled at its physical size, or (None, None).

    The tiling is per object: tiles per UV unit = object["skinbake_uv_size"] [m] / tile size,
    read with an Attribute node, so one material serves meshes of any UV scale.  normal.png
    holds the slopes of the physical heights, so strength 1 at the true tile size is physical.
    area = 1 / (n . N_smooth), the micro-surface area per unit of macro surface: a normal map
    alone loses the light that falls on the extra area of tilted facets (a Lambert surface under
    the face maps, mean n_z 0.87, rendered 13 % dark); with it the mean irradiance is exact."""
    d = m["detail"]
    tr.far = None
    tr.detail_co = None
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
    tr.detail_co = co
    nm = tr.node("ShaderNodeNormalMap", (-1000, -700), space="TANGENT")
    tr.link(t.outputs["Color"], nm.inputs["Color"])
    if far:
        _far_setup(tr, m, co, size, nm)
    tr.nrm_diffuse = None
    dimg = diffuse_normal_image(m, img)
    if dimg is not None:
        td = tr.tex(dimg, co, (-1300, -400), label="normal.png blurred by the subsurface radius")
        nd = tr.node("ShaderNodeNormalMap", (-1000, -400), space="TANGENT")
        tr.link(td.outputs["Color"], nd.inputs["Color"])
        if nm.inputs["Strength"].is_linked:
            tr.link(nm.inputs["Strength"].links[0].from_socket, nd.inputs["Strength"])
        tr.nrm_diffuse = nd.outputs["Normal"]
    nz = tr.math("MAXIMUM", tr.vmath("DOT_PRODUCT", nm.outputs["Normal"], geo.outputs["Normal"], (-800, -850)),
                 0.2, loc=(-650, -850))
    area = tr.math("DIVIDE", 1.0, nz, loc=(-500, -850))
    area.node.label = "micro-surface area 1 / n_z"
    if tr.far is not None:        # the normal map fades out, and with it the area it loses
        area = tr.math("MULTIPLY_ADD", tr.math("SUBTRACT", 1.0, area, loc=(-500, -1000)), tr.far[0], area,
                       loc=(-350, -900))
    return nm.outputs["Normal"], area


def diffuse_normal_image(m, img):
    """normal.png with its slopes blurred by the subsurface light's spread (docs/relief.md section
    7): the diffuse light leaves 0.1-1 mm from where it entered, so to first order it sees the
    relief convolved with Rd(r).  Here Rd(r) is a Gaussian of the set's luminance-weighted mean
    exit radius (sss_radius_m; mean radius = sigma sqrt(pi / 2)), applied to the slopes n_x / n_z,
    n_y / n_z as three periodic box passes per axis (the tile is periodic; plain Python, as
    Debian's Blender has no numpy: about 10 s for 1024 px).  None when
    SKINBAKE_DIFFUSE_RELIEF=sharp or without a radius."""
    if os.environ.get("SKINBAKE_DIFFUSE_RELIEF") == "sharp" or "sss_radius_m" not in m:
        return None
    w, h = img.size
    r = sum(k * float(x) for k, x in zip((0.2126, 0.7152, 0.0722), m["sss_radius_m"]))
    texel = float(m["detail"]["tile_mm"]) * 1e-3 / w
    sigma = r / math.sqrt(math.pi / 2) / texel
    if not sigma > 0.5 or w != h:
        return None
    px = list(img.pixels)
    sx = [0.0] * (w * h)
    sy = [0.0] * (w * h)
    for i in range(w * h):
        nz = max(2 * px[4 * i + 2] - 1, 0.05)
        sx[i] = (2 * px[4 * i] - 1) / nz
        sy[i] = (2 * px[4 * i + 1] - 1) / nz
    # The Gaussian as three periodic box passes per axis: variance 3 (b^2 - 1) / 12 = sigma^2.
    b = max(1, int(round(math.sqrt(4 * sigma * sigma + 1))) | 1)
    b = min(b, w - 1 if w % 2 == 0 else w)
    for a in (sx, sy):
        for _ in range(3):
            _box(a, w, 1, w, b)        # rows
            _box(a, w, w, 1, b)        # columns
    q = bytearray()
    for y in range(h - 1, -1, -1):    # Blender's pixels run bottom row first; a PNG's top first
        q += b"\0"
        for x in range(w):
            i = y * w + x
            k = 1 / math.sqrt(1 + sx[i] * sx[i] + sy[i] * sy[i])
            for v in (0.5 + 0.5 * sx[i] * k, 0.5 + 0.5 * sy[i] * k, 0.5 + 0.5 * k):
                q += struct.pack(">H", int(round(min(max(v, 0.0), 1.0) * 65535)))
    raw = bytes(q)
    chunk = lambda t, b: struct.pack(">I", len(b)) + t + b + struct.pack(">I", zlib.crc32(t + b) & 0xffffffff)
    path = os.path.join(m["_dir"], "normal_diffuse.png")
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))
    d = bpy.data.images.load(path, check_existing=False)
    d.colorspace_settings.name = "Non-Color"
    print(f"skinbake: {path}: normal.png blurred by a Gaussian of mean radius {r * 1e3:.3g} mm for the "
          "subsurface closures (SKINBAKE_DIFFUSE_RELIEF=sharp keeps normal.png)")
    return d


def _box(a, n, step, stride, b):
    """Box filter of odd width b, periodic, over the n lines of n values of a (value j of line i
    at i * stride + j * step)."""
    r = b // 2
    for i in range(n):
        o = i * stride
        line = [a[o + j * step] for j in range(n)]
        s = sum(line[j % n] for j in range(-r, r + 1))
        for j in range(n):
            a[o + j * step] = s / b
            s += line[(j + r + 1) % n] - line[(j - r) % n]


def _pixel_m_per_m():
    """(ortho, k): the scene camera's pixel footprint, k [m] for an orthographic camera, k [m per
    m of distance] for a perspective one; None without a camera."""
    sc = bpy.context.scene
    cam = sc.camera
    if cam is None or cam.type != "CAMERA":
        return None
    res = sc.render.resolution_x * sc.render.resolution_percentage / 100.0
    if cam.data.type == "ORTHO":
        return True, cam.data.ortho_scale / res
    return False, 2.0 * math.tan(cam.data.angle / 2.0) / res


def _far_setup(tr, m, co, size, nm):
    """Fade the normal map out and keep its spread as roughness where a primary cell (one block of
    roughness_far.png) goes below a pixel: f = 0 while a block spans FAR_NEAR_PX pixels or more,
    1 at FAR_FAR_PX and less (linear in between, in the camera's view distance for a perspective
    camera, a constant for an orthographic one).  Sets tr.far = (f, alpha_relief) for
    far_roughness, or None (no map in the set, no camera, or SKINBAKE_FAR=off)."""
    if "roughness_far" not in m["files"] or os.environ.get("SKINBAKE_FAR") == "off":
        return
    px = _pixel_m_per_m()
    if px is None:
        print("skinbake: no scene camera yet, so the far roughness (roughness_far.png) is not used")
        return
    e = m["files"]["roughness_far"]
    n = int(e["width"])
    img = load_image(m, "roughness_far")
    ft = tr.tex(img, co, (-1300, -1000), label="roughness_far.png (alpha_relief)")
    # One block [m] = size [m per UV unit] / (tiles per UV unit) / n = tile / n.
    block = float(m["detail"]["tile_mm"]) * 1e-3 / n
    ortho, k = px
    if ortho:
        cells = block / k
        f = min(max((FAR_NEAR_PX - cells) / (FAR_NEAR_PX - FAR_FAR_PX), 0.0), 1.0)
        if f == 0.0:
            return
        fs = f
    else:
        cd = tr.node("ShaderNodeCameraData", (-1300, -1250))
        mr = tr.node("ShaderNodeMapRange", (-1100, -1250), label="far: relief below a pixel")
        mr.clamp = True
        tr.link(cd.outputs["View Distance"], mr.inputs[0])
        mr.inputs[1].default_value = block / (FAR_NEAR_PX * k)
        mr.inputs[2].default_value = block / (FAR_FAR_PX * k)
        mr.inputs[3].default_value = 0.0
        mr.inputs[4].default_value = 1.0
        fs = mr.outputs[0]
    strength = tr.math("SUBTRACT", 1.0, fs, loc=(-1100, -600))
    tr.link(strength, nm.inputs["Strength"])
    tr.far = (fs, ft.outputs["Color"])


def far_roughness(tr, r, loc=(-200, 600)):
    """Perceptual roughness r (a socket or a number; GGX alpha = r^2) with the relief's spread
    added where it is below a pixel: alpha^2 = alpha_skin^2 + f alpha_relief^2, so r' =
    (r^4 + f alpha_relief^2)^(1/4).  r itself when the set has no far roughness."""
    far = getattr(tr, "far", None)
    if far is None:
        return r
    f, a = far
    x, y = loc
    r4 = tr.math("POWER", r, 4.0, loc=(x - 600, y))
    a2 = tr.math("MULTIPLY", a, a, loc=(x - 600, y - 150))
    fa2 = tr.math("MULTIPLY", a2, f, loc=(x - 400, y - 150))
    tot = tr.math("ADD", r4, fa2, loc=(x - 200, y))
    out = tr.math("POWER", tot, 0.25, loc=(x, y))
    out.node.label = "roughness with the far relief"
    return out


def far_area_mean(tr, area_mean):
    """The mean micro-area correction 1 / mean n_z of the normal map, faded with it where the far
    roughness replaces it (a constant f: orthographic camera; with a perspective camera the
    correction stays, at most 1 / mean n_z - 1, about 5 % on the face, too bright far away)."""
    far = getattr(tr, "far", None)
    if far is None or not isinstance(far[0], float):
        return area_mean
    return 1.0 + (1.0 - far[0]) * (area_mean - 1.0)


def cavity(tr, m, shader, loc=(1300, 200)):
    """The skin's shader darkened by the relief's cavity (cavity.png tiled like normal.png): a
    Mix Shader between nothing (a black emission) at factor 0 and the skin at 1, i.e. the skin's
    light times the cavity, so furrows and pores are darker than their slopes alone make them
    (docs/relief.md).  The shader itself when the set has no cavity map, the detail is off, or
    SKINBAKE_CAVITY=off."""
    co = getattr(tr, "detail_co", None)
    if co is None or "cavity" not in m["files"] or os.environ.get("SKINBAKE_CAVITY") == "off":
        return shader
    x, y = loc
    img = load_image(m, "cavity")
    t = tr.tex(img, co, (x - 600, y - 300), label="cavity.png (ambient occlusion of the relief)")
    fac = t.outputs["Color"]
    far = getattr(tr, "far", None)
    if far is not None:
        # Where the relief is below a pixel the map fades to its mean with the normal map (f = 1:
        # the mean alone), as the far roughness replaces the slopes: no sample noise far away.
        mean = float(m["files"]["cavity"].get("mean", 1.0))
        fac = tr.math("MULTIPLY_ADD", tr.math("SUBTRACT", mean, fac, loc=(x - 450, y - 450)), far[0], fac,
                      loc=(x - 300, y - 400))
    black = tr.node("ShaderNodeEmission", (x - 300, y - 150), label="nothing")
    black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    black.inputs["Strength"].default_value = 0.0
    mix = tr.node("ShaderNodeMixShader", (x, y), label="skin x cavity")
    tr.link(fac, mix.inputs["Fac"])
    tr.link(black.outputs["Emission"], mix.inputs[1])
    tr.link(shader, mix.inputs[2])
    return mix.outputs["Shader"]
