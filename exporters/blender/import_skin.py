# import_skin.py: import a skinbake image set (`skinbake export blender`) into Blender.
#
# Works as an add-on (File > Import > skinbake image set) and from the command line, on a new
# demo scene or on your own .blend file:
#
#   blender -b my.blend --python-exit-code 1 --python exporters/blender/import_skin.py -- SET \
#       --objects Head,Body --mode exact --save out.blend
#   blender -b --factory-startup --python-exit-code 1 --python exporters/blender/import_skin.py -- SET \
#       --mode general --render sphere.png                   # demo sphere, camera and sun
#
# Two material modes:
#   general  Principled BSDF (random-walk subsurface, index, roughness, normal map); with a fit in
#            the manifest (format 1, "general_fit"), a mixture of closures whose view-dependent
#            weights reproduce the baked BRDF.  Any lights, Cycles and EEVEE.
#   exact    The baked BRDF itself for every sun, point and spot lamp: one view layer per lamp
#            (the other lamps excluded), the lamp's direction or position stored in the layer and
#            read with an Attribute node (type View Layer), a Diffuse BSDF whose colour is pi * f_r
#            from brdf_lut.exr at that layer's cos(light), cos(view) and delta_phi per shading
#            point, and the compositor summing the layers.  Cycles' diffuse closure returns
#            colour/pi * E * cos_l, so each lamp gives exactly E cos_l f_r; its falloff, cone and
#            shadows stay Cycles' job.  World light and area lamps are shaded by the general
#            material in one more view layer.
# Blender's SVM shader nodes see no light direction (and this Debian build has no OSL), which is
# why the exact mode needs a view layer per lamp.  Node inputs are looked up by their Blender 3.x
# and 4.x names.  Errors in the image set, a missing object or an object without UVs raise
# SkinbakeError; on the command line they print "import_skin.py: error: ..." and exit with status 2.
import json
import math
import os
import sys

import bpy

bl_info = {
    "name": "skinbake image set",
    "author": "skinbake",
    "version": (1, 1, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > skinbake image set (manifest.json)",
    "description": "Skin materials from a skinbake image set (general Principled fit, or exact per lamp)",
    "category": "Import-Export",
}
__version__ = "1.1.0"
FORMAT = "skinbake-blender-image-set"
FORMAT_VERSIONS = (1,)          # manifest "format_version" values this importer understands
FILES = ("albedo", "brdf_lut", "roughness", "height", "normal")
PREFIX = "skinbake"             # names of everything the importer adds to a scene start with it


class SkinbakeError(Exception):
    """Bad input: an image set, an object name, a mesh without UVs, a scene EEVEE cannot do."""


class ImageSetError(SkinbakeError):
    """The image set is missing, incomplete, corrupt or of an unknown version."""


def say(msg):
    print(f"import_skin.py: {msg}")


# ------------------------------------------------------------------ reading the image set

def _need(d, key, kind, where):
    if key not in d:
        raise ImageSetError(f"{where}: missing \"{key}\"")
    v = d[key]
    if kind is float and isinstance(v, int) and not isinstance(v, bool):
        v = float(v)
    if not isinstance(v, kind):
        raise ImageSetError(f"{where}: \"{key}\" is {v!r}, expected {kind.__name__}")
    return v


def read_manifest(directory):
    """Parse and check DIR/manifest.json; returns the dict."""
    directory = os.path.abspath(directory)
    if not os.path.isdir(directory):
        raise ImageSetError(f"{directory}: no such image-set directory")
    path = os.path.join(directory, "manifest.json")
    if not os.path.isfile(path):
        raise ImageSetError(f"{path}: missing (not a skinbake image set; write one with "
                            "`skinbake export blender`)")
    try:
        with open(path, encoding="utf-8") as f:
            m = json.load(f)
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise ImageSetError(f"{path}: unreadable or not JSON ({e})") from None
    if not isinstance(m, dict) or m.get("format") != FORMAT:
        raise ImageSetError(f"{path}: \"format\" is not \"{FORMAT}\"")
    ver = m.get("format_version")
    if ver not in FORMAT_VERSIONS:
        raise ImageSetError(f"{path}: format_version {ver!r} is not supported by import_skin.py "
                            f"{__version__} (supported: {', '.join(map(str, FORMAT_VERSIONS))})")
    _need(m, "ior", float, path)
    _need(m, "roughness", float, path)
    for key in ("sss_radius_m", "albedo_rgb"):
        v = _need(m, key, list, path)
        if len(v) != 3 or not all(isinstance(x, (int, float)) and x >= 0 for x in v):
            raise ImageSetError(f"{path}: \"{key}\" must be 3 numbers >= 0, got {v!r}")
    files = _need(m, "files", dict, path)
    for role in FILES:
        e = _need(files, role, dict, f"{path}: files")
        _need(e, "path", str, f"{path}: files.{role}")
        _need(e, "width", int, f"{path}: files.{role}")
        _need(e, "height", int, f"{path}: files.{role}")
        p = os.path.join(directory, e["path"])
        if not os.path.isfile(p) or os.path.getsize(p) == 0:
            raise ImageSetError(f"{p}: missing or empty (listed in manifest.json as {role})")
        (check_exr if p.lower().endswith(".exr") else check_png)(p, e["width"], e["height"])
    lut = _need(m, "brdf_lut", dict, path)
    nc, nphi = _need(lut, "cos_nodes", int, f"{path}: brdf_lut"), _need(lut, "phi_nodes", int, f"{path}: brdf_lut")
    if nc < 2 or nphi < 2 or files["brdf_lut"]["width"] != nc * nphi or files["brdf_lut"]["height"] != nc:
        raise ImageSetError(f"{path}: brdf_lut {nc} x {nphi} nodes does not match files.brdf_lut size")
    ex = _need(m, "exact", dict, path)
    s = _need(ex, "sun_direction", list, f"{path}: exact")
    if len(s) != 3 or s[2] <= 0:
        raise ImageSetError(f"{path}: exact.sun_direction must be 3 numbers with z > 0, got {s!r}")
    _need(_need(m, "detail", dict, path), "flat", bool, f"{path}: detail")
    m["_dir"] = directory
    return m


# Blender's readers can hang on a truncated EXR (measured with 3.4.1: a 300-byte albedo.exr made
# it spin forever) and accept some damaged files silently, so every file is checked here first.
_EXR_LINES = {0: 1, 1: 1, 2: 1, 3: 16, 4: 32, 5: 16, 6: 32, 7: 32, 8: 32, 9: 256}


def _read_bytes(path):
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as e:
        raise ImageSetError(f"{path}: {e.strerror}") from None


def check_exr(path, width, height):
    """Structure of a single-part scanline EXR: header, size, and every chunk inside the file."""
    import struct
    b = _read_bytes(path)
    bad = lambda why: ImageSetError(f"{path}: corrupt OpenEXR file ({why})")   # noqa: E731
    if len(b) < 8 or b[:4] != b"\x76\x2f\x31\x01":
        raise bad("no OpenEXR magic number")
    if struct.unpack_from("<I", b, 4)[0] & 0x1a00:
        raise bad("tiled, deep or multi-part: expected one scanline part")
    pos, attrs = 8, {}
    try:
        while b[pos] != 0:
            name_end = b.index(b"\0", pos)
            type_end = b.index(b"\0", name_end + 1)
            (size,) = struct.unpack_from("<i", b, type_end + 1)
            start = type_end + 5
            if size < 0 or start + size > len(b):
                raise bad("attribute runs past the end")
            attrs[b[pos:name_end].decode("latin-1")] = b[start:start + size]
            pos = start + size
        pos += 1
        x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"])
        comp = attrs["compression"][0]
    except (IndexError, KeyError, ValueError, struct.error):
        raise bad("truncated or incomplete header") from None
    if (x1 - x0 + 1, y1 - y0 + 1) != (width, height):
        raise ImageSetError(f"{path}: {x1 - x0 + 1}x{y1 - y0 + 1} px, manifest.json says {width}x{height}")
    if comp not in _EXR_LINES:
        raise bad(f"unknown compression {comp}")
    chunks = -(-height // _EXR_LINES[comp])
    if pos + 8 * chunks > len(b):
        raise bad("truncated offset table")
    for off in struct.unpack_from(f"<{chunks}Q", b, pos):
        if off + 8 > len(b) or off + 8 + struct.unpack_from("<i", b, off + 4)[0] > len(b):
            raise bad("truncated pixel data")


def check_png(path, width, height):
    """Every chunk's CRC, IHDR size and the complete image data of a PNG."""
    import struct
    import zlib
    b = _read_bytes(path)
    bad = lambda why: ImageSetError(f"{path}: corrupt PNG file ({why})")       # noqa: E731
    if b[:8] != b"\x89PNG\r\n\x1a\n":
        raise bad("no PNG signature")
    pos, idat, ihdr, end = 8, [], None, False
    while pos + 12 <= len(b) and not end:
        (n,) = struct.unpack_from(">I", b, pos)
        kind, data = b[pos + 4:pos + 8], b[pos + 8:pos + 8 + n]
        if len(data) != n or pos + 12 + n > len(b):
            raise bad("truncated chunk")
        if zlib.crc32(kind + data) != struct.unpack_from(">I", b, pos + 8 + n)[0]:
            raise bad(f"CRC error in {kind.decode('latin-1')}")
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", data)
        elif kind == b"IDAT":
            idat.append(data)
        end = kind == b"IEND"
        pos += 12 + n
    if ihdr is None or not end:
        raise bad("no IHDR or IEND")
    w, h, depth, ctype = ihdr[:4]
    if (w, h) != (width, height):
        raise ImageSetError(f"{path}: {w}x{h} px, manifest.json says {width}x{height}")
    chans = {0: 1, 2: 3, 4: 2, 6: 4}.get(ctype)
    if chans is None or depth not in (8, 16) or ihdr[6] != 0:
        raise bad(f"colour type {ctype} at {depth} bits, interlace {ihdr[6]}: not written by skinbake")
    try:
        raw = zlib.decompress(b"".join(idat))
    except zlib.error as e:
        raise bad(f"image data: {e}") from None
    if len(raw) != h * (1 + w * chans * depth // 8):
        raise bad("image data has the wrong size")


def load_image(m, role, data=True):
    """Load one file of the set and check Blender read it at the size the manifest states."""
    e = m["files"][role]
    p = os.path.join(m["_dir"], e["path"])
    try:
        img = bpy.data.images.load(p, check_existing=True)
    except RuntimeError as err:
        raise ImageSetError(f"{p}: Blender cannot read it ({err})") from None
    if data:                    # PNGs default to sRGB: data maps must not be converted
        img.colorspace_settings.name = "Non-Color"
    w, h = img.size
    if (w, h) != (e["width"], e["height"]):
        bpy.data.images.remove(img)
        raise ImageSetError(f"{p}: Blender read {w}x{h} px, manifest.json says "
                            f"{e['width']}x{e['height']} (corrupt or replaced file)")
    return img


# ------------------------------------------------------------------ node helpers

def sock(sockets, *names):
    """The first socket found under any of NAMES (names differ between Blender 3.x and 4.x)."""
    for n in names:
        if n in sockets:
            return sockets[n]
    return None


class _Tree:
    def __init__(self, mat):
        mat.use_nodes = True
        self.nt = mat.node_tree
        self.nt.nodes.clear()

    def node(self, kind, loc, label=None, **props):
        n = self.nt.nodes.new(kind)
        n.location = loc
        if label:
            n.label = label
        for k, v in props.items():
            setattr(n, k, v)
        return n

    def link(self, src, dst):
        self.nt.links.new(src, dst)

    def _in(self, n, i, x):
        if isinstance(x, bpy.types.NodeSocket):
            self.link(x, n.inputs[i])
        else:
            n.inputs[i].default_value = x

    def math(self, op, a, b=0.0, c=None, loc=(0, 0), clamp=False):
        n = self.node("ShaderNodeMath", loc, operation=op, use_clamp=clamp)
        self._in(n, 0, a)
        self._in(n, 1, b)
        if c is not None:
            self._in(n, 2, c)
        return n.outputs[0]

    def vmath(self, op, a, b=None, loc=(0, 0), scale=None):
        n = self.node("ShaderNodeVectorMath", loc, operation=op)
        self._in(n, 0, a)
        if b is not None:
            self._in(n, 1, b)
        if scale is not None:
            self._in(n, n.inputs.find("Scale"), scale)
        return n.outputs["Value" if op in ("DOT_PRODUCT", "LENGTH") else "Vector"]

    def xyz(self, x, y, z, loc, label=None):
        n = self.node("ShaderNodeCombineXYZ", loc, label)
        for i, v in enumerate((x, y, z)):
            self._in(n, i, v)
        return n.outputs["Vector"]

    def mix(self, a, b, f, loc):
        """(1 - f) a + f b on colours (f in [0, 1]; values are not clamped)."""
        n = self.node("ShaderNodeMix", loc, data_type="RGBA", blend_type="MIX")
        self._in(n, 0, f)
        self._in(n, 6, a)
        self._in(n, 7, b)
        return n.outputs[2]

    def attr(self, kind, name, loc, label=None):
        return self.node("ShaderNodeAttribute", loc, label or name, attribute_type=kind, attribute_name=name)

    def tex(self, img, vector, loc, extension="REPEAT", label=None, interpolation="Linear"):
        t = self.node("ShaderNodeTexImage", loc, label, image=img, interpolation=interpolation,
                      extension=extension)
        if vector is not None:
            self.link(vector, t.inputs["Vector"])
        return t


# ------------------------------------------------------------------ detail maps

UV_SIZE_PROP = PREFIX + "_uv_size"     # object property: metres per UV unit (Attribute, type Object)


def _detail_normal(tr, m, no_detail, geo):
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


def _stamp(mat, m, mode):
    mat["skinbake_importer"] = __version__
    mat["skinbake_format_version"] = m["format_version"]
    mat["skinbake_mode"] = mode
    mat["skinbake_image_set"] = m["_dir"]


# ------------------------------------------------------------------ general mode

# Diffuse albedo that Cycles 3.x renders per unit Principled Base Color with RANDOM_WALK
# subsurface, under uniform white light, view along the normal, roughness 0 (measured with
# Blender 3.4.1, 64 px, 128-256 spp, +-0.3 %): the random-walk albedo inversion runs 0.5-2 % low.
_K0_ALBEDO = (0.05, 0.15, 0.3, 0.6, 0.8)
_K0 = (0.995, 0.991, 0.983, 0.981, 0.987)
_K_PER_ROUGHNESS = 0.0607       # the Principled diffuse retro-reflection term, same measurements


def _interp(xs, ys, x):
    if x <= xs[0]:
        return ys[0]
    if x >= xs[-1]:
        return ys[-1]
    i = max(j for j in range(len(xs) - 1) if xs[j] <= x)
    return ys[i] + (ys[i + 1] - ys[i]) * (x - xs[i]) / (xs[i + 1] - xs[i])


def albedo_calibration(albedo, roughness):
    """Rendered / requested diffuse albedo for Blender 3.x, per channel: k0(albedo) + 0.0607 *
    roughness.  It rises further toward grazing views (+2 % at 60 deg).  Blender 4 has a
    different Principled BSDF that was not measured: 1 there."""
    if bpy.app.version >= (4, 0, 0):
        return [1.0] * len(albedo)
    r = min(max(roughness, 0.0), 1.0)
    return [_interp(_K0_ALBEDO, _K0, a) + _K_PER_ROUGHNESS * r for a in albedo]


def _general_principled(tr, m, nrm, unit_scale, no_specular, calibrate, area_mean):
    """One Principled BSDF: albedo (calibrated), random-walk radius, index, roughness map."""
    bsdf = tr.node("ShaderNodeBsdfPrincipled", (200, 300))
    bsdf.subsurface_method = "RANDOM_WALK"
    uv = tr.node("ShaderNodeTexCoord", (-1500, 600))
    alb = tr.tex(load_image(m, "albedo", data=False), uv.outputs["UV"], (-600, 700), label="albedo.exr")
    base = alb.outputs["Color"]
    k = albedo_calibration(m["albedo_rgb"], float(m["roughness"])) if calibrate else [1.0] * 3
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
    bsdf.inputs["Subsurface Radius"].default_value = [x / unit_scale for x in m["sss_radius_m"]]
    n = float(m["ior"])
    bsdf.inputs["IOR"].default_value = n
    spec = sock(bsdf.inputs, "Specular")                           # 3.x: 0.5 <-> F0 = 0.04
    if spec is not None:
        spec.default_value = 0.0 if no_specular else ((n - 1) / (n + 1)) ** 2 / 0.08
    elif sock(bsdf.inputs, "Specular IOR Level") is not None:      # 4.x: 0.5 = as the IOR says
        sock(bsdf.inputs, "Specular IOR Level").default_value = 0.0 if no_specular else 0.5
    rough = tr.tex(load_image(m, "roughness"), uv.outputs["UV"], (-600, 400), label="roughness.png")
    tr.link(rough.outputs["Color"], bsdf.inputs["Roughness"])
    if nrm is not None:
        tr.link(nrm, bsdf.inputs["Normal"])
    return bsdf.outputs["BSDF"]


# Rendered / requested albedo of the Principled random-walk subsurface closure in Blender 3.4
# (roughness 0) under a sun, from the same measurements as _K0: _K0 is its white-furnace value,
# which includes the exit's Disney light falloff, whose cosine-weighted mean is 1 - 1/42.
_K_SSS = tuple(k / (1.0 - 1.0 / 42.0) for k in _K0)


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


def _general_fit(tr, m, nrm, area, geo, unit_scale, no_specular, calibrate, area_mean):
    """The closure mixture fitted at export time (manifest general_fit, blender_fit.h)."""
    f = m["general_fit"]
    N = nrm if nrm is not None else geo.outputs["Normal"]
    cos_v = tr.math("ADD", tr.vmath("DOT_PRODUCT", N, geo.outputs["Incoming"], (-1500, 1300)), 0.0,
                    loc=(-1300, 1300), clamp=True)
    nodes = [float(x) for x in f["cos_view_nodes"]]

    def sss_scale(c, v):
        k = _interp(_K0_ALBEDO, _K_SSS, v) if calibrate and bpy.app.version < (4, 0, 0) else 1.0
        return v / k * area_mean
    col_s = _ramp(tr, cos_v, nodes, f["subsurface_rgb"], sss_scale, (-1000, 1500), "subsurface colour s(cos_view)")
    col_g = _ramp(tr, cos_v, nodes, f["glossy_rgb"], lambda c, v: v, (-1000, 1100), "glossy colour g(cos_view)")
    if area is not None:
        col_g = tr.vmath("SCALE", col_g, loc=(-700, 1100), scale=area)
    sss = tr.node("ShaderNodeBsdfPrincipled", (-400, 1700), "subsurface: s(v) (1 - F_L / 2)")
    sss.subsurface_method = "RANDOM_WALK"
    tr.link(col_s, sss.inputs["Base Color"])
    if sock(sss.inputs, "Subsurface Color"):
        tr.link(col_s, sock(sss.inputs, "Subsurface Color"))
    sock(sss.inputs, "Subsurface Weight", "Subsurface").default_value = 1.0
    sss.inputs["Subsurface Radius"].default_value = [x / unit_scale for x in m["sss_radius_m"]]
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
        add = tr.node("ShaderNodeAddShader", (100, 1200))
        tr.link(out, add.inputs[0])
        tr.link(sp.outputs["BSDF"], add.inputs[1])
        out = add.outputs["Shader"]
        closures.append(sp)
    if nrm is not None:
        for c in closures:
            tr.link(nrm, c.inputs["Normal"])
    return out


def _general_shader(tr, m, nrm, area, geo, unit_scale, no_specular, calibrate):
    """The fitted mixture when the manifest has one (Blender 3.x), else one Principled BSDF."""
    # Subsurface light is averaged over many facets, so its micro-area correction is the mean one.
    area_mean = 1.0
    if nrm is not None and m["detail"].get("mean_normal_z"):
        area_mean = 1.0 / float(m["detail"]["mean_normal_z"])
    if isinstance(m.get("general_fit"), dict) and bpy.app.version < (4, 0, 0):
        return _general_fit(tr, m, nrm, area, geo, unit_scale, no_specular, calibrate, area_mean)
    return _general_principled(tr, m, nrm, unit_scale, no_specular, calibrate, area_mean)


def build_general(m, name="skinbake general", no_detail=False, no_specular=False, unit_scale=1.0,
                  calibrate=True):
    """A material for any lights and engines (see _general_shader)."""
    mat = bpy.data.materials.new(name)
    tr = _Tree(mat)
    out = tr.node("ShaderNodeOutputMaterial", (1600, 0))
    geo = tr.node("ShaderNodeNewGeometry", (-2300, 300))
    nrm, area = _detail_normal(tr, m, no_detail, geo)
    tr.link(_general_shader(tr, m, nrm, area, geo, unit_scale, no_specular, calibrate), out.inputs["Surface"])
    _stamp(mat, m, "general")
    return mat


# ------------------------------------------------------------------ exact mode

VL_EXACT = PREFIX + "_exact"            # view-layer properties the exact material reads
VL_DIR = PREFIX + "_light_dir"          # unit vector toward a sun (0 for point and spot lamps)
VL_POS = PREFIX + "_light_pos"          # lamp position (point and spot)
VL_POINT = PREFIX + "_light_point"      # 1 for point and spot lamps, 0 for suns


def _lut_sample(tr, img, nc, nphi, cl, cv, dphi, x0, y0):
    """pi f_r from the atlas at cos_light, cos_view in [0, 1] and dphi in [0, pi]: bilinear in the
    two neighbouring delta_phi tiles, then linear between them (blender_lut_sample in C).

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
    v00 = tr.math("DIVIDE", tr.math("ADD", i0, 0.5, loc=(x0 + 600, y0 - 50)), nc, loc=(x0 + 750, y0 - 50))
    tiles = []
    for ds in (0, 1):
        rows = []
        for di in (0, 1):
            cols = []
            for dj in (0, 1):
                k = 4 * ds + 2 * di + dj
                u = tr.math("ADD", u00, (ds * nc + dj) / width, loc=(x0 + 1050, y0 + 400 - 150 * k))
                v = tr.math("ADD", v00, di / nc, loc=(x0 + 1050, y0 + 330 - 150 * k))
                te = tr.tex(img, tr.xyz(u, v, 0.0, (x0 + 1200, y0 + 400 - 150 * k)), (x0 + 1350, y0 + 400 - 150 * k),
                            "EXTEND", f"brdf_lut.exr {'s0+1' if ds else 's0'} i{'+1' if di else ''} j{'+1' if dj else ''}",
                            interpolation="Closest")
                cols.append(te.outputs["Color"])
            rows.append(tr.mix(cols[0], cols[1], tx, (x0 + 1650, y0 + 350 - 300 * (2 * ds + di))))
        tiles.append(tr.mix(rows[0], rows[1], ty, (x0 + 1850, y0 + 200 - 600 * ds)))
    return tr.mix(tiles[0], tiles[1], t, (x0 + 2050, y0 - 100))


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
    tr = _Tree(mat)
    out = tr.node("ShaderNodeOutputMaterial", (2400, 0))
    geo = tr.node("ShaderNodeNewGeometry", (-2300, 300))
    nrm, area = _detail_normal(tr, m, no_detail, geo)
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
    col = _lut_sample(tr, lutimg, nc, nphi, cl, cv, dphi, -450, 0)
    if area is not None:
        col = tr.vmath("SCALE", col, loc=(1800, 0), scale=area)
    dif = tr.node("ShaderNodeBsdfDiffuse", (2000, 0))
    tr.link(col, dif.inputs["Color"])
    if nrm is not None:
        tr.link(nrm, dif.inputs["Normal"])
    gen = _general_shader(tr, m, nrm, area, geo, unit_scale, no_specular, calibrate)
    mix = tr.node("ShaderNodeMixShader", (2200, 0), "general (world, area lamps) | exact (one lamp)")
    tr.link(fexact, mix.inputs["Fac"])
    tr.link(gen, mix.inputs[1])
    tr.link(dif.outputs["BSDF"], mix.inputs[2])
    tr.link(mix.outputs["Shader"], out.inputs["Surface"])
    _stamp(mat, m, "exact")
    return mat


# ------------------------------------------------------------------ objects

def find_objects(names):
    """The mesh objects called NAMES, or SkinbakeError naming the missing ones."""
    obs, missing = [], []
    for n in names:
        ob = bpy.data.objects.get(n)
        if ob is None:
            missing.append(n)
        elif ob.type != "MESH":
            raise SkinbakeError(f"--objects: '{n}' is a {ob.type.lower()} object, not a mesh")
        else:
            obs.append(ob)
    if missing:
        have = sorted(o.name for o in bpy.data.objects if o.type == "MESH")
        shown = ", ".join(have[:20]) + (" ..." if len(have) > 20 else "")
        raise SkinbakeError(f"--objects: no object named {', '.join(repr(x) for x in missing)} "
                            f"(mesh objects in the file: {shown or 'none'})")
    return obs


def generate_uvs(ob):
    """Smart UV Project on OB (object mode afterwards)."""
    vl = bpy.context.view_layer
    prev = vl.objects.active
    if bpy.context.object is not None and bpy.context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    vl.objects.active = ob
    for o in vl.objects:
        o.select_set(o == ob)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.uv.smart_project(island_margin=0.002)
    bpy.ops.object.mode_set(mode="OBJECT")
    vl.objects.active = prev


def measure_uv_size(ob, unit_scale=1.0):
    """(metres per UV unit, 10th and 90th percentile over the surface) of OB's render UV map:
    sqrt(world surface area / UV area) over all faces, and per face weighted by area; None when
    the UV area is zero."""
    me = ob.data
    uvl = next((u for u in me.uv_layers if u.active_render), me.uv_layers.active)
    if uvl is None:
        return None
    mw = ob.matrix_world
    co = [mw @ v.co for v in me.vertices]
    uv = uvl.data
    a3 = a2 = 0.0
    faces = []
    for p in me.polygons:
        idx = list(p.loop_indices)
        v0 = co[me.loops[idx[0]].vertex_index]
        u0 = uv[idx[0]].uv
        f3 = f2 = 0.0
        for k in range(1, len(idx) - 1):          # fan triangles
            v1, v2 = co[me.loops[idx[k]].vertex_index], co[me.loops[idx[k + 1]].vertex_index]
            f3 += (v1 - v0).cross(v2 - v0).length / 2
            u1, u2 = uv[idx[k]].uv, uv[idx[k + 1]].uv
            f2 += abs((u1.x - u0.x) * (u2.y - u0.y) - (u2.x - u0.x) * (u1.y - u0.y)) / 2
        a3 += f3
        a2 += f2
        if f2 > 0 and f3 > 0:
            faces.append((math.sqrt(f3 / f2), f3))
    if a2 <= 0 or not faces:
        return None
    faces.sort()
    total, acc, q = sum(f[1] for f in faces), 0.0, {}
    for d, w in faces:
        acc += w
        for p in (0.1, 0.9):
            if p not in q and acc >= p * total:
                q[p] = d
    k = unit_scale
    return math.sqrt(a3 / a2) * k, q[0.1] * k, q[0.9] * k


def prepare_objects(obs, m, mode, no_detail, uv_size=None, gen_uvs=False, unit_scale=1.0):
    """Check UVs where the detail map needs them (or generate them) and store each object's UV
    size [m per UV unit] in its skinbake_uv_size property."""
    detail = not (no_detail or m["detail"].get("flat") or not m["detail"].get("tile_mm"))
    for ob in obs:
        if detail and not ob.data.uv_layers:
            if not gen_uvs:
                raise SkinbakeError(f"object '{ob.name}' has no UV map: the detail normal map needs one "
                                    "(add UVs, or pass --generate-uvs for a Smart UV Project, or --no-detail)")
            generate_uvs(ob)
            say(f"'{ob.name}' had no UV map: generated one with Smart UV Project (the detail map has seams "
                "at the island borders)")
        if not detail:
            continue
        if uv_size is not None:
            ob[UV_SIZE_PROP] = float(uv_size)
            say(f"'{ob.name}': UV size {uv_size:.4g} m per UV unit (--uv-size)")
            continue
        r = measure_uv_size(ob, unit_scale)
        if r is None:
            raise SkinbakeError(f"object '{ob.name}': its UV map has zero area; fix the UVs or give --uv-size")
        s, lo, hi = r
        ob[UV_SIZE_PROP] = s
        say(f"'{ob.name}': UV size {s:.4g} m per UV unit (measured: sqrt(surface area / UV area)); "
            f"detail tile {float(m['detail']['tile_mm']):g} mm")
        if hi > 1.25 * lo:
            say(f"note: the UV density of '{ob.name}' varies: {lo:.3g} to {hi:.3g} m per UV unit over 80% of "
                "its surface, so the detail maps are at their true size only where it is "
                f"{s:.3g}; give --uv-size for the part that matters (e.g. the face)")


def assign(obs, mat):
    """MAT into every material slot of each object (one slot if it has none).  The materials it
    replaces get a fake user, so that saving the file keeps them."""
    for ob in obs:
        if not ob.material_slots:
            ob.data.materials.append(mat)
        for s in ob.material_slots:
            old = s.material
            if old is not None and old != mat and not old.name.startswith(PREFIX):
                if not old.use_fake_user:
                    old.use_fake_user = True
                    say(f"material '{old.name}' of '{ob.name}' kept in the file (fake user)")
            s.material = mat


# ------------------------------------------------------------------ exact mode: view layers

EXACT_TYPES = ("SUN", "POINT", "SPOT")
AMBIENT_LAYER = PREFIX + ": world and area lights"


def _renders_in(ob, vl):
    return ob.name in vl.objects and not ob.hide_render


def world_is_dark(world):
    """True when WORLD adds no light: none, or a plain black background."""
    if world is None:
        return True
    if not world.use_nodes:
        return max(world.color) <= 0.0
    out = next((n for n in world.node_tree.nodes if n.type == "OUTPUT_WORLD" and n.is_active_output), None)
    if out is None or not out.inputs["Surface"].is_linked:
        return True
    n = out.inputs["Surface"].links[0].from_node
    if n.type != "BACKGROUND" or n.inputs["Color"].is_linked or n.inputs["Strength"].is_linked:
        return False
    return n.inputs["Strength"].default_value <= 0 or max(n.inputs["Color"].default_value[:3]) <= 0


def _copy_layer_flags(src, dst):
    """dst's collection flags (exclude, holdout, indirect only, hide) as in src, by name."""
    for a, b in zip(src.children, dst.children):
        if a.name == b.name:
            b.exclude, b.holdout, b.indirect_only = a.exclude, a.holdout, a.indirect_only
            b.hide_viewport = a.hide_viewport
            _copy_layer_flags(a, b)


def _find_layer_collection(lc, name):
    if lc.name == name:
        return lc
    for c in lc.children:
        r = _find_layer_collection(c, name)
        if r is not None:
            return r
    return None


def _light_collection(scene, ob):
    """A collection of its own for lamp OB (so a view layer can exclude just this lamp)."""
    parent = bpy.data.collections.get(PREFIX + " lamps")
    if parent is None:
        parent = bpy.data.collections.new(PREFIX + " lamps")
    if parent.name not in scene.collection.children:
        scene.collection.children.link(parent)
    name = f"{PREFIX} lamp: {ob.name}"
    c = bpy.data.collections.get(name)
    if c is None:
        c = bpy.data.collections.new(name)
    if c.name not in parent.children:
        parent.children.link(c)
    if list(ob.users_collection) != [c]:
        for u in list(ob.users_collection):
            u.objects.unlink(ob)
        c.objects.link(ob)
    return c


def _remove_layers(scene):
    for vl in [v for v in scene.view_layers if v.name.startswith(PREFIX + ":")]:
        scene.view_layers.remove(vl)


def setup_exact_layers(scene, source=None, engine=None):
    """One view layer per sun, point and spot lamp that renders in SOURCE (the other lamps
    excluded, the world switched off, the lamp stored in the layer's properties), one layer for
    the world and area lamps (general material) when there is such light, and a compositor that
    sums them.  SOURCE is switched off for rendering.  Returns the list of new layer names."""
    from mathutils import Vector
    engine = engine or scene.render.engine
    source = source or bpy.context.view_layer
    if source.name.startswith(PREFIX + ":"):
        source = next((v for v in scene.view_layers if not v.name.startswith(PREFIX + ":")), source)
    _remove_layers(scene)
    source.update()                          # matrix_world of lamps moved by a script
    lamps = [o for o in scene.objects if o.type == "LIGHT" and _renders_in(o, source)]
    exact = [o for o in lamps if o.data.type in EXACT_TYPES]
    areas = [o for o in lamps if o.data.type not in EXACT_TYPES]
    lit_world = not world_is_dark(scene.world)
    if engine == "BLENDER_EEVEE" and lit_world and exact:
        raise SkinbakeError("exact mode in EEVEE needs a black world: EEVEE cannot switch the world off "
                            "in the per-lamp view layers, so its light would be counted once per lamp "
                            "(render with Cycles, or set the world colour to black)")
    if not exact:
        say("exact mode: no sun, point or spot lamp renders in this scene: everything is shaded by the "
            "general material")
    colls = {o.name: _light_collection(scene, o) for o in exact}
    made = []

    def new_layer(name):
        vl = scene.view_layers.new(name)
        _copy_layer_flags(source.layer_collection, vl.layer_collection)
        for c in colls.values():
            lc = _find_layer_collection(vl.layer_collection, c.name)
            if lc is not None:
                lc.exclude = True
        vl.use = True
        made.append(vl.name)
        return vl

    for o in exact:
        vl = new_layer(f"{PREFIX}: {o.name}")
        _find_layer_collection(vl.layer_collection, colls[o.name].name).exclude = False
        vl.use_sky = False                   # Cycles: no world light in a per-lamp layer
        mw = o.matrix_world
        vl[VL_EXACT] = 1.0
        if o.data.type == "SUN":              # a sun shines along its local -Z
            vl[VL_DIR] = list((mw.to_quaternion() @ Vector((0.0, 0.0, 1.0))).normalized())
            vl[VL_POS] = [0.0, 0.0, 0.0]
            vl[VL_POINT] = 0.0
        else:
            vl[VL_DIR] = [0.0, 0.0, 0.0]
            vl[VL_POS] = list(mw.translation)
            vl[VL_POINT] = 1.0
        soft = o.data.angle if o.data.type == "SUN" else o.data.shadow_soft_size
        note = ""
        if soft > 0:
            note = (f"; its {'angle' if o.data.type == 'SUN' else 'radius'} "
                    f"{math.degrees(soft) if o.data.type == 'SUN' else soft:.3g}"
                    f"{' deg' if o.data.type == 'SUN' else ' m'} softens shadows, the table uses its centre")
        say(f"exact mode: view layer '{vl.name}' for {o.data.type.lower()} lamp '{o.name}'{note}")
    if lit_world or areas:
        vl = new_layer(AMBIENT_LAYER)
        vl[VL_EXACT] = 0.0
        what = (["the world"] if lit_world else []) + [f"area lamp '{o.name}'" for o in areas]
        say(f"exact mode: {' and '.join(what)} shaded by the general material (view layer '{vl.name}')")
    source.use = False
    for v in scene.view_layers:
        if v.use and v.name not in made:
            say(f"note: view layer '{v.name}' also renders and is not part of the exact sum")
    _compositor_sum(scene, source, made)
    scene[PREFIX + "_exact_layers"] = made
    say(f"exact mode: the compositor sums {len(made)} view layer(s); view layer '{source.name}' is "
        "switched off for rendering (run the importer again after adding, removing or moving lamps)")
    return made


def _compositor_sum(scene, source, layers):
    scene.use_nodes = True
    scene.render.use_compositing = True
    nt = scene.node_tree
    for n in [n for n in nt.nodes if n.name.startswith(PREFIX)]:
        nt.nodes.remove(n)
    comp = next((n for n in nt.nodes if n.type == "COMPOSITE"), None)
    if comp is None:
        comp = nt.nodes.new("CompositorNodeComposite")
        comp.location = (600, 0)
    if not layers:
        return
    total = None
    for i, name in enumerate(layers):
        rl = nt.nodes.new("CompositorNodeRLayers")
        rl.name = f"{PREFIX} layer {i}"
        rl.label = name
        rl.layer = name
        rl.location = (-600, -300 * i)
        if total is None:
            total = rl.outputs["Image"]
            continue
        add = nt.nodes.new("CompositorNodeMixRGB")
        add.name = f"{PREFIX} sum {i}"
        add.blend_type = "ADD"
        add.use_alpha = False
        add.inputs[0].default_value = 1.0
        add.location = (-300 + 150 * i, -300 * i)
        nt.links.new(total, add.inputs[1])
        nt.links.new(rl.outputs["Image"], add.inputs[2])
        total = add.outputs["Image"]
    relinked = False
    for link in list(nt.links):
        fn = link.from_node
        if fn.type == "R_LAYERS" and not fn.name.startswith(PREFIX) and fn.layer == source.name \
                and link.from_socket.name == "Image":
            nt.links.new(total, link.to_socket)
            relinked = True
    if not relinked:
        nt.links.new(total, comp.inputs["Image"])


def fix_denoiser(scene):
    """Debian's Cycles has no OpenImageDenoise (nor a GPU denoiser): a render with denoising on
    fails ('Build without OpenImageDenoiser'), so switch it off and say so."""
    try:
        import _cycles
        if getattr(_cycles, "with_openimagedenoise", True):
            return
    except ImportError:
        return
    if scene.cycles.use_denoising:
        scene.cycles.use_denoising = False
        say("this Blender has no OpenImageDenoise: Cycles denoising switched off (it would fail the render)")


# ------------------------------------------------------------------ demo scene and render

def _direction(elev_deg, azim_deg):
    e, a = math.radians(elev_deg), math.radians(azim_deg)
    return (math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e))


def render_settings(scene, res=None, samples=None, engine=None):
    """Cycles CPU (or EEVEE), fixed seed, denoiser off, Standard view transform."""
    if engine:
        scene.render.engine = engine
    cy = scene.cycles
    cy.device = "CPU"
    if samples:
        cy.samples = samples
        scene.eevee.taa_render_samples = samples
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.seed = 0
    cy.use_animated_seed = False
    if res:
        scene.render.resolution_x = scene.render.resolution_y = res
        scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"


def build_scene(m, kind, res, samples, world, sun_strength, view=None, engine="CYCLES"):
    """A fresh scene: object at the origin, orthographic camera along the manifest's reference
    view direction, the manifest's sun."""
    from mathutils import Vector
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    render_settings(scene, res, samples, engine)
    wd = bpy.data.worlds.new("World")
    scene.world = wd
    wd.use_nodes = True
    wd.node_tree.nodes["Background"].inputs["Color"].default_value = (world, world, world, 1.0)
    if kind == "plane":
        bpy.ops.mesh.primitive_plane_add(size=0.2)
        scale = 0.05
    elif kind == "box":               # closed, so random-walk subsurface has an inside
        bpy.ops.mesh.primitive_cube_add(size=1.0)
        obj = bpy.context.active_object
        obj.scale = (0.2, 0.2, 0.05)
        obj.location = (0, 0, -0.025)
        bpy.ops.object.transform_apply(location=True, rotation=True, scale=True)
        scale = 0.04
    elif kind == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=0.1)
        bpy.ops.object.shade_smooth()
        scale = 0.23
    else:
        raise ValueError(kind)
    obj = bpy.context.active_object
    obj.name = "skin"
    ref = m["exact"].get("reference", {})
    vdir = Vector(_direction(*view) if view else ref.get("view_direction", _direction(60, -90))).normalized()
    cd = bpy.data.cameras.new("Camera")
    cd.type, cd.ortho_scale = "ORTHO", scale
    cam = bpy.data.objects.new("Camera", cd)
    scene.collection.objects.link(cam)
    cam.location = vdir * 1.0
    cam.rotation_euler = (-vdir).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam
    if sun_strength > 0:
        sd = bpy.data.lights.new("Sun", "SUN")
        sd.energy = sun_strength       # Cycles: irradiance normal to the sun [W/m^2]
        sd.angle = 0.0
        sun = bpy.data.objects.new("Sun", sd)
        scene.collection.objects.link(sun)
        sun.rotation_euler = Vector(m["exact"]["sun_direction"]).normalized().to_track_quat("Z", "Y").to_euler()
    return scene, obj


def render(scene, out):
    """Render SCENE to OUT (.exr: linear float; else 8-bit sRGB PNG) and return the mean RGB of the
    centre quarter, read back from the file (Render Result has no pixels in background mode)."""
    import time
    fmt = scene.render.image_settings
    if out.lower().endswith(".exr"):
        fmt.file_format, fmt.color_depth = "OPEN_EXR", "32"
    else:
        fmt.file_format, fmt.color_depth = "PNG", "8"
    fmt.color_mode = "RGB"
    scene.render.filepath = out
    t0 = time.time()
    bpy.ops.render.render(write_still=True)
    print(f"SKINBAKE_RENDER_SECONDS {time.time() - t0:.2f}")
    return centre_mean(out)


def centre_mean(path):
    img = bpy.data.images.load(path, check_existing=False)
    img.colorspace_settings.name = "Non-Color"
    w, h, ch = img.size[0], img.size[1], img.channels
    px = list(img.pixels)
    acc, n = [0.0, 0.0, 0.0], 0
    for y in range(h * 3 // 8, h * 5 // 8):
        for x in range(w * 3 // 8, w * 5 // 8):
            i = (y * w + x) * ch
            for c in range(3):
                acc[c] += px[i + c]
            n += 1
    bpy.data.images.remove(img)
    return [a / n for a in acc]


def import_set(m, scene, obs, mode, no_detail=False, no_specular=False, calibrate=True, uv_size=None,
               gen_uvs=False, engine=None):
    """Everything the command line and the add-on do: materials onto OBS, and for the exact mode
    the per-lamp view layers.  Returns the material."""
    unit = scene.unit_settings.scale_length or 1.0
    prepare_objects(obs, m, mode, no_detail, uv_size, gen_uvs, unit)
    kw = dict(no_detail=no_detail, no_specular=no_specular, unit_scale=unit, calibrate=calibrate)
    mat = build_exact(m, **kw) if mode == "exact" else build_general(m, **kw)
    assign(obs, mat)
    say(f"material '{mat.name}'" + (f" on {', '.join(repr(o.name) for o in obs)}" if obs else
                                     " (not assigned: no --objects)"))
    if mode == "exact":
        setup_exact_layers(scene, bpy.context.view_layer, engine)
    fix_denoiser(scene)
    return mat


# ------------------------------------------------------------------ command line

def main(argv):
    import argparse

    class Parser(argparse.ArgumentParser):
        def error(self, message):
            raise SkinbakeError(message)

    ap = Parser(prog="import_skin.py", description=f"Import a skinbake image set (importer {__version__}).")
    ap.add_argument("dir", help="image-set directory (holds manifest.json), or its manifest.json")
    ap.add_argument("--mode", choices=("general", "exact"), default="general",
                    help="material mode (default general)")
    ap.add_argument("--objects", metavar="A,B", help="mesh objects that get the material (default: the demo object)")
    ap.add_argument("--scene", choices=("sphere", "plane", "box", "none"), default=None,
                    help="demo scene to build (default sphere with --render or --save and no .blend "
                         "file or --objects, else none)")
    ap.add_argument("--render", metavar="FILE", help="render to FILE (.exr: linear float for measuring; else 8-bit sRGB PNG)")
    ap.add_argument("--save", metavar="FILE", help="save the result as a .blend (image paths relative)")
    ap.add_argument("--pack", action="store_true", help="pack the images into the .blend")
    ap.add_argument("--engine", choices=("CYCLES", "BLENDER_EEVEE"), default=None,
                    help="render engine (default: the file's; Cycles for the demo scene)")
    ap.add_argument("--res", type=int, default=None, help="render size [px] (demo default 64)")
    ap.add_argument("--samples", type=int, default=None, help="samples (demo default 16)")
    ap.add_argument("--world", type=float, default=0.0, help="demo world radiance (default 0)")
    ap.add_argument("--sun-strength", type=float, default=None,
                    help="demo sun irradiance [W/m^2], 0 = no sun (default: the manifest's)")
    ap.add_argument("--view", nargs=2, type=float, metavar=("ELEV", "AZIM"), default=None,
                    help="demo camera elevation and azimuth [deg] (default: the manifest's reference view)")
    ap.add_argument("--uv-size", type=float, default=None,
                    help="metres per UV unit for tiling the detail maps (default: measured per object)")
    ap.add_argument("--generate-uvs", action="store_true", help="give objects without UVs a Smart UV Project")
    ap.add_argument("--no-detail", action="store_true", help="leave out the normal map")
    ap.add_argument("--no-specular", action="store_true", help="general mode without the specular layer")
    ap.add_argument("--no-calibration", action="store_true",
                    help="general mode: Base Color = albedo, without the Cycles 3.x correction")
    a = ap.parse_args(argv)
    if a.uv_size is not None and not (a.uv_size > 0):
        raise SkinbakeError(f"--uv-size = {a.uv_size} must be > 0 metres per UV unit")
    for k in ("res", "samples"):
        v = getattr(a, k)
        if v is not None and not 1 <= v <= 16384:
            raise SkinbakeError(f"--{k} = {v} is out of range [1, 16384]")
    d = a.dir[:-len("manifest.json")] if a.dir.endswith("manifest.json") else a.dir
    m = read_manifest(d or ".")
    say(f"{__version__}: {m['_dir']} (format {m['format_version']}, "
        f"{'flat' if m['detail']['flat'] else 'textured'} detail)")
    have_file = bool(bpy.data.filepath)
    kind = a.scene or ("sphere" if (a.render or a.save) and not have_file and not a.objects else "none")
    if kind != "none" and have_file:
        raise SkinbakeError(f"--scene {kind} builds a new scene and would discard {bpy.data.filepath}; "
                            "use --objects to put the material on the file's own meshes")
    obs = []
    if a.objects:
        obs = find_objects([x.strip() for x in a.objects.split(",") if x.strip()])
    scene = bpy.context.scene
    if kind != "none":
        strength = m["exact"].get("sun_strength_w_m2", 3.0) if a.sun_strength is None else a.sun_strength
        scene, obj = build_scene(m, kind, a.res or 64, a.samples or 16, a.world, strength, a.view,
                                 a.engine or "CYCLES")
        obs = obs or [obj]
    else:
        if a.engine:
            scene.render.engine = a.engine
        if a.res:
            scene.render.resolution_x = scene.render.resolution_y = a.res
            scene.render.resolution_percentage = 100
        if a.samples:
            scene.cycles.samples = scene.eevee.taa_render_samples = a.samples
    import_set(m, scene, obs, a.mode, a.no_detail, a.no_specular, not a.no_calibration, a.uv_size,
               a.generate_uvs, a.engine or scene.render.engine)
    if a.save:
        path = os.path.abspath(a.save)
        bpy.ops.wm.save_as_mainfile(filepath=path)
        if a.pack:
            bpy.ops.file.pack_all()
        else:
            bpy.ops.file.make_paths_relative()
        bpy.ops.wm.save_as_mainfile(filepath=path)
        say(f"saved {path}")
    if a.render:
        if scene.camera is None:
            raise SkinbakeError("--render: the scene has no camera")
        mean = render(scene, os.path.abspath(a.render))
        print("SKINBAKE_CENTER " + " ".join(f"{x:.6f}" for x in mean))


# ------------------------------------------------------------------ add-on

try:
    from bpy_extras.io_utils import ImportHelper
except ImportError:             # pragma: no cover - outside Blender
    ImportHelper = object


class IMPORT_OT_skinbake(bpy.types.Operator, ImportHelper):
    """Import a skinbake image set (select its manifest.json); the material goes to the selected meshes"""
    bl_idname = "import_scene.skinbake"
    bl_label = "Import skinbake image set"
    bl_options = {"REGISTER", "UNDO"}
    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="manifest.json", options={"HIDDEN"})
    mode: bpy.props.EnumProperty(
        name="Mode",
        items=(("GENERAL", "General", "Principled BSDF fitted to the bake: any lights, Cycles and EEVEE"),
               ("EXACT", "Exact", "The baked BRDF for every sun, point and spot lamp (one view layer per "
                                  "lamp, summed in the compositor)")),
        default="GENERAL")
    uv_size: bpy.props.FloatProperty(name="UV size [m]", default=0.0, min=0.0,
                                     description="Metres covered by one UV unit (0: measured per object)")
    detail: bpy.props.BoolProperty(name="Detail normal map", default=True)
    generate_uvs: bpy.props.BoolProperty(name="Generate missing UVs", default=False,
                                         description="Smart UV Project on meshes without UVs")

    def execute(self, context):
        obs = [o for o in context.selected_objects if o.type == "MESH"]
        try:
            m = read_manifest(os.path.dirname(self.filepath))
            mat = import_set(m, context.scene, obs, self.mode.lower(), no_detail=not self.detail,
                             uv_size=self.uv_size or None, gen_uvs=self.generate_uvs)
        except SkinbakeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"skinbake: {mat.name} on {len(obs)} object(s)")
        return {"FINISHED"}


def _menu(self, context):
    self.layout.operator(IMPORT_OT_skinbake.bl_idname, text="skinbake image set (manifest.json)")


def register():
    bpy.utils.register_class(IMPORT_OT_skinbake)
    bpy.types.TOPBAR_MT_file_import.append(_menu)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_menu)
    bpy.utils.unregister_class(IMPORT_OT_skinbake)


if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    try:
        main(args)
    except SkinbakeError as e:
        print(f"import_skin.py: error: {e}", file=sys.stderr)
        sys.stdout.flush()
        sys.stderr.flush()
        sys.exit(2)
