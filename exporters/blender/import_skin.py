# import_skin.py: import a skinbake image set (`skinbake export blender`) into Blender.
#
# Works as an add-on (File > Import > skinbake image set) and from the command line:
#
#   blender -b --factory-startup --python-exit-code 1 --python import_skin.py -- DIR \
#       [--mode general|exact] [--scene sphere|plane|box|none] [--render OUT.exr|OUT.png]
#       [--save OUT.blend] [--res PX] [--samples N] [--world W] [--sun-strength E]
#       [--uv-size M] [--no-detail] [--no-specular] [--pack]
#
# Two material modes:
#   general  Principled BSDF: albedo, random-walk subsurface radius, index, roughness map and
#            normal map.  Works under any lights; Cycles' own random walk re-creates the
#            subsurface transport, so it is faithful but not the baked BRDF itself.
#   exact    Diffuse BSDF whose colour is pi * f_r looked up in brdf_lut.exr at the shading
#            point's cos(view) (Geometry > Incoming), cos(light) and delta_phi for ONE sun whose
#            direction is a constant in the node tree.  Cycles' diffuse closure returns
#            colour/pi * E * cos_l, so that sun gives exactly E cos_l f_r, for any geometry and
#            camera.  Other lamps and the world are shaded as if they came from that sun.
# Blender's SVM shader nodes see no light direction (and this Debian build has no OSL), which is
# why the exact mode needs the sun direction baked in.  Node inputs are looked up by their
# Blender 3.x and 4.x names.  Errors in the image set raise ImageSetError; on the command line
# they print "import_skin.py: error: ..." and exit with status 2.
import json
import math
import os
import sys

import bpy

bl_info = {
    "name": "skinbake image set",
    "author": "skinbake",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > skinbake image set (manifest.json)",
    "description": "Skin materials from a skinbake image set (general Principled or exact one-sun)",
    "category": "Import-Export",
}
__version__ = "1.0.0"
FORMAT = "skinbake-blender-image-set"
FORMAT_VERSIONS = (1,)          # manifest "format_version" values this importer understands
FILES = ("albedo", "brdf_lut", "roughness", "height", "normal")


class ImageSetError(Exception):
    """The image set is missing, incomplete, corrupt or of an unknown version."""


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
        self.x = 0

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
        return n.outputs["Value" if op == "DOT_PRODUCT" else "Vector"]

    def xyz(self, x, y, z, loc, label=None):
        n = self.node("ShaderNodeCombineXYZ", loc, label)
        for i, v in enumerate((x, y, z)):
            self._in(n, i, v)
        return n.outputs["Vector"]

    def tex(self, img, vector, loc, extension="REPEAT", label=None):
        t = self.node("ShaderNodeTexImage", loc, label, image=img, interpolation="Linear",
                      extension=extension)
        if vector is not None:
            self.link(vector, t.inputs["Vector"])
        return t


def _detail_normal(tr, m, uv_size_m, no_detail):
    """Normal Map node output from normal.png tiled at its physical size, or None when flat."""
    d = m["detail"]
    if no_detail or d.get("flat") or not d.get("tile_mm"):
        return None
    img = load_image(m, "normal")
    uv = tr.node("ShaderNodeTexCoord", (-1500, -500))
    mp = tr.node("ShaderNodeMapping", (-1300, -500), "tile: UV unit / tile size")
    rep = uv_size_m * 1000.0 / float(d["tile_mm"])        # tiles per UV unit
    mp.inputs["Scale"].default_value = (rep, rep, 1.0)
    tr.link(uv.outputs["UV"], mp.inputs["Vector"])
    t = tr.tex(img, mp.outputs["Vector"], (-1100, -500), label="normal.png (OpenGL +Y)")
    nm = tr.node("ShaderNodeNormalMap", (-800, -500), space="TANGENT")
    tr.link(t.outputs["Color"], nm.inputs["Color"])
    print(f"import_skin.py: detail normal map, {rep:.4g} tiles per UV unit")
    return nm.outputs["Normal"]


def _stamp(mat, m, mode):
    mat["skinbake_importer"] = __version__
    mat["skinbake_format_version"] = m["format_version"]
    mat["skinbake_mode"] = mode


# Diffuse albedo that Cycles 3.x renders per unit Principled Base Color with RANDOM_WALK
# subsurface, under uniform white light, view along the normal, roughness 0 (measured with
# Blender 3.4.1, 64 px, 128-256 spp, +-0.3 %): the random-walk albedo inversion runs 0.5-2 % low.
_K0_ALBEDO = (0.05, 0.15, 0.3, 0.6, 0.8)
_K0 = (0.995, 0.991, 0.983, 0.981, 0.987)
_K_PER_ROUGHNESS = 0.0607       # the Principled diffuse retro-reflection term, same measurements


def albedo_calibration(albedo, roughness):
    """Rendered / requested diffuse albedo for Blender 3.x, per channel: k0(albedo) + 0.0607 *
    roughness.  It rises further toward grazing views (+2 % at 60 deg).  Blender 4 has a
    different Principled BSDF that was not measured: 1 there."""
    if bpy.app.version >= (4, 0, 0):
        return [1.0] * len(albedo)
    r = min(max(roughness, 0.0), 1.0)
    out = []
    for a in albedo:
        xs, ys = _K0_ALBEDO, _K0
        if a <= xs[0]:
            k0 = ys[0]
        elif a >= xs[-1]:
            k0 = ys[-1]
        else:
            i = max(j for j in range(len(xs) - 1) if xs[j] <= a)
            k0 = ys[i] + (ys[i + 1] - ys[i]) * (a - xs[i]) / (xs[i + 1] - xs[i])
        out.append(k0 + _K_PER_ROUGHNESS * r)
    return out


def build_general(m, name="skinbake general", uv_size_m=0.1, no_detail=False, no_specular=False,
                  unit_scale=1.0, calibrate=True):
    """Principled BSDF material for any lights.  Base Color = the set's albedo divided by
    albedo_calibration(albedo, roughness) (unless calibrate is False), so the rendered diffuse albedo
    matches the baked one."""
    mat = bpy.data.materials.new(name)
    tr = _Tree(mat)
    out = tr.node("ShaderNodeOutputMaterial", (600, 0))
    bsdf = tr.node("ShaderNodeBsdfPrincipled", (200, 0))
    bsdf.subsurface_method = "RANDOM_WALK"
    uv = tr.node("ShaderNodeTexCoord", (-1500, 200))
    alb = tr.tex(load_image(m, "albedo", data=False), uv.outputs["UV"], (-600, 300), label="albedo.exr")
    base = alb.outputs["Color"]
    k = albedo_calibration(m["albedo_rgb"], float(m["roughness"])) if calibrate else [1.0] * 3
    if k != [1.0] * 3:
        base = tr.vmath("MULTIPLY", base, [1.0 / x for x in k], loc=(-300, 300))
        base.node.label = "albedo / (" + ", ".join(f"{x:.4f}" for x in k) + ") Cycles 3.x calibration"
    tr.link(base, bsdf.inputs["Base Color"])
    if sock(bsdf.inputs, "Subsurface Color"):                      # 3.x only
        tr.link(base, sock(bsdf.inputs, "Subsurface Color"))
    # 3.x: "Subsurface" is the weight and multiplies the radius; 4.x: Weight and Scale.
    sock(bsdf.inputs, "Subsurface Weight", "Subsurface").default_value = 1.0
    if sock(bsdf.inputs, "Subsurface Scale"):
        sock(bsdf.inputs, "Subsurface Scale").default_value = 1.0
    r = [x / unit_scale for x in m["sss_radius_m"]]                # metres -> scene units
    bsdf.inputs["Subsurface Radius"].default_value = r
    n = float(m["ior"])
    bsdf.inputs["IOR"].default_value = n
    spec = sock(bsdf.inputs, "Specular")                           # 3.x: 0.5 <-> F0 = 0.04
    if spec is not None:
        spec.default_value = 0.0 if no_specular else ((n - 1) / (n + 1)) ** 2 / 0.08
    elif sock(bsdf.inputs, "Specular IOR Level") is not None:      # 4.x: 0.5 = as the IOR says
        sock(bsdf.inputs, "Specular IOR Level").default_value = 0.0 if no_specular else 0.5
    rough = tr.tex(load_image(m, "roughness"), uv.outputs["UV"], (-600, 0), label="roughness.png")
    tr.link(rough.outputs["Color"], bsdf.inputs["Roughness"])
    nrm = _detail_normal(tr, m, uv_size_m, no_detail)
    if nrm is not None:
        tr.link(nrm, bsdf.inputs["Normal"])
    tr.link(bsdf.outputs["BSDF"], out.inputs["Surface"])
    _stamp(mat, m, "general")
    return mat


def build_exact(m, sun_dir=None, name="skinbake exact", uv_size_m=0.1, no_detail=False):
    """Diffuse BSDF with colour pi * f_r(cos_v, cos_l, delta_phi) for one sun.

    sun_dir points toward the sun in world space (default: the manifest's)."""
    lutimg = load_image(m, "brdf_lut")
    nc, nphi = m["brdf_lut"]["cos_nodes"], m["brdf_lut"]["phi_nodes"]
    width = nc * nphi
    s = sun_dir if sun_dir is not None else m["exact"]["sun_direction"]
    ln = math.sqrt(sum(x * x for x in s))
    s = [x / ln for x in s]
    mat = bpy.data.materials.new(name)
    tr = _Tree(mat)
    out = tr.node("ShaderNodeOutputMaterial", (1400, 0))
    geo = tr.node("ShaderNodeNewGeometry", (-1500, 300))
    nrm = _detail_normal(tr, m, uv_size_m, no_detail)
    N = nrm if nrm is not None else geo.outputs["Normal"]
    I = geo.outputs["Incoming"]                                   # unit vector toward the viewer
    L = tr.xyz(s[0], s[1], s[2], (-1500, 0), label="sun direction (toward the sun)")
    cv_raw = tr.vmath("DOT_PRODUCT", N, I, (-1200, 400))
    cl_raw = tr.vmath("DOT_PRODUCT", N, L, (-1200, 0))
    cv = tr.math("ADD", cv_raw, 0.0, loc=(-1000, 400), clamp=True)   # clamp to [0, 1]
    cl = tr.math("ADD", cl_raw, 0.0, loc=(-1000, 0), clamp=True)
    # delta_phi: angle between the tangent-plane projections of I and L (0 = back toward the
    # light).  A zero projection (view or light along N) gives 90 deg, where f_r has no azimuth.
    vp = tr.vmath("NORMALIZE", tr.vmath("SUBTRACT", I, tr.vmath("SCALE", N, loc=(-1200, 250), scale=cv_raw),
                                       loc=(-1050, 250)), loc=(-900, 250))
    lp = tr.vmath("NORMALIZE", tr.vmath("SUBTRACT", L, tr.vmath("SCALE", N, loc=(-1200, 150), scale=cl_raw),
                                       loc=(-1050, 150)), loc=(-900, 150))
    dphi = tr.math("ARCCOSINE", tr.vmath("DOT_PRODUCT", vp, lp, (-750, 200)), loc=(-600, 200))
    # Tile index s0 and blend t between tiles s0 and s0 + 1 (layout in manifest "brdf_lut").
    sc = tr.math("MULTIPLY", dphi, (nphi - 1) / math.pi, loc=(-450, 200))
    s0 = tr.math("MINIMUM", tr.math("FLOOR", sc, loc=(-300, 250)), nphi - 2, loc=(-150, 250))
    t = tr.math("SUBTRACT", sc, s0, loc=(0, 150))
    # u = (s0 * nc + cos_v * (nc - 1) + 0.5) / width: texel centres, never across a tile edge.
    x = tr.math("MULTIPLY_ADD", cv, nc - 1, 0.5, loc=(-600, 400))
    u0 = tr.math("DIVIDE", tr.math("MULTIPLY_ADD", s0, nc, x, loc=(0, 400)), width, loc=(150, 400))
    u1 = tr.math("ADD", u0, nc / width, loc=(300, 450))
    v = tr.math("MULTIPLY_ADD", cl, (nc - 1) / nc, 0.5 / nc, loc=(-600, 0))   # v = 0 is the bottom row
    ta = tr.tex(lutimg, tr.xyz(u0, v, 0.0, (300, 300)), (450, 300), "EXTEND", "brdf_lut.exr tile s0")
    tb = tr.tex(lutimg, tr.xyz(u1, v, 0.0, (450, 500)), (600, 500), "EXTEND", "brdf_lut.exr tile s0+1")
    one_minus_t = tr.math("SUBTRACT", 1.0, t, loc=(300, 100))
    col = tr.vmath("ADD", tr.vmath("SCALE", ta.outputs["Color"], loc=(800, 300), scale=one_minus_t),
                   tr.vmath("SCALE", tb.outputs["Color"], loc=(800, 450), scale=t), loc=(950, 350))
    dif = tr.node("ShaderNodeBsdfDiffuse", (1150, 0))
    tr.link(col, dif.inputs["Color"])
    if nrm is not None:
        tr.link(nrm, dif.inputs["Normal"])
    tr.link(dif.outputs["BSDF"], out.inputs["Surface"])
    _stamp(mat, m, "exact")
    mat["skinbake_sun_direction"] = s
    return mat


def scene_sun_direction(scene):
    """Direction toward the first sun lamp of SCENE, or None (a sun shines along its local -Z)."""
    from mathutils import Vector
    for ob in scene.objects:
        if ob.type == "LIGHT" and ob.data.type == "SUN":
            return list(ob.matrix_world.to_quaternion() @ Vector((0.0, 0.0, 1.0)))
    return None


# ------------------------------------------------------------------ demo scene and render

def _direction(elev_deg, azim_deg):
    e, a = math.radians(elev_deg), math.radians(azim_deg)
    return (math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e))


def build_scene(m, kind, res, samples, world, sun_strength, view=None):
    """A fresh scene: object at the origin, orthographic camera along the manifest's reference
    view direction, the manifest's sun; Cycles CPU, denoiser off, Standard view transform."""
    from mathutils import Vector
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = samples
    cy.use_adaptive_sampling = False
    cy.use_denoising = False          # Debian's Cycles has no OpenImageDenoise
    cy.seed = 0
    cy.use_animated_seed = False
    scene.render.resolution_x = scene.render.resolution_y = res
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    wd = bpy.data.worlds.new("World")
    scene.world = wd
    wd.use_nodes = True
    wd.node_tree.nodes["Background"].inputs["Color"].default_value = (world, world, world, 1.0)

    obj = None
    if kind == "plane":
        bpy.ops.mesh.primitive_plane_add(size=0.2)
        scale, uv_size = 0.05, 0.2
    elif kind == "box":               # closed, so random-walk subsurface has an inside
        bpy.ops.mesh.primitive_cube_add(size=1.0)
        obj = bpy.context.active_object
        obj.scale = (0.2, 0.2, 0.05)
        obj.location = (0, 0, -0.025)
        bpy.ops.object.transform_apply(location=True, rotation=True, scale=True)
        scale, uv_size = 0.04, 0.2
    elif kind == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=0.1)
        bpy.ops.object.shade_smooth()
        scale, uv_size = 0.23, 0.63
    else:
        raise ValueError(kind)
    obj = bpy.context.active_object

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
    return scene, obj, uv_size


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


# ------------------------------------------------------------------ command line

def main(argv):
    import argparse
    ap = argparse.ArgumentParser(prog="import_skin.py",
                                 description=f"Import a skinbake image set (importer {__version__}).")
    ap.add_argument("dir", help="image-set directory (holds manifest.json)")
    ap.add_argument("--mode", choices=("general", "exact"), default="general",
                    help="material mode (default general)")
    ap.add_argument("--scene", choices=("sphere", "plane", "box", "none"), default=None,
                    help="demo scene to build (default sphere with --render or --save, else none)")
    ap.add_argument("--render", metavar="FILE", help="render to FILE (.exr: linear float for measuring; else 8-bit sRGB PNG)")
    ap.add_argument("--save", metavar="FILE", help="save the result as a .blend (image paths relative)")
    ap.add_argument("--pack", action="store_true", help="pack the images into the .blend")
    ap.add_argument("--res", type=int, default=64, help="render size [px] (default 64)")
    ap.add_argument("--samples", type=int, default=16, help="Cycles samples (default 16)")
    ap.add_argument("--world", type=float, default=0.0, help="uniform world radiance (default 0)")
    ap.add_argument("--sun-strength", type=float, default=None,
                    help="sun irradiance [W/m^2], 0 = no sun (default: the manifest's)")
    ap.add_argument("--view", nargs=2, type=float, metavar=("ELEV", "AZIM"), default=None,
                    help="camera elevation and azimuth [deg] (default: the manifest's reference view)")
    ap.add_argument("--uv-size", type=float, default=None,
                    help="metres per UV unit for tiling the detail maps (default: the demo object's, else 0.1)")
    ap.add_argument("--no-detail", action="store_true", help="leave out the normal map")
    ap.add_argument("--no-specular", action="store_true", help="general mode without the specular layer")
    ap.add_argument("--no-calibration", action="store_true",
                    help="general mode: Base Color = albedo, without the Cycles 3.x correction")
    a = ap.parse_args(argv)

    m = read_manifest(a.dir)
    print(f"import_skin.py {__version__}: {m['_dir']} (format {m['format_version']}, "
          f"{'flat' if m['detail']['flat'] else 'textured'} detail)")
    kind = a.scene or ("sphere" if (a.render or a.save) else "none")
    scene, obj, uv_size = bpy.context.scene, None, 0.1
    if kind != "none":
        strength = m["exact"].get("sun_strength_w_m2", 3.0) if a.sun_strength is None else a.sun_strength
        scene, obj, uv_size = build_scene(m, kind, a.res, a.samples, a.world, strength, a.view)
    if a.uv_size is not None:
        uv_size = a.uv_size
    unit = scene.unit_settings.scale_length or 1.0
    if a.mode == "exact":
        mat = build_exact(m, uv_size_m=uv_size, no_detail=a.no_detail)
    else:
        mat = build_general(m, uv_size_m=uv_size, no_detail=a.no_detail, no_specular=a.no_specular,
                            unit_scale=unit, calibrate=not a.no_calibration)
    print(f"import_skin.py: material '{mat.name}'")
    if obj is not None:
        obj.data.materials.append(mat)
    if a.save:
        path = os.path.abspath(a.save)
        bpy.ops.wm.save_as_mainfile(filepath=path)
        if a.pack:
            bpy.ops.file.pack_all()
        else:
            bpy.ops.file.make_paths_relative()
        bpy.ops.wm.save_as_mainfile(filepath=path)
        print(f"import_skin.py: saved {path}")
    if a.render:
        mean = render(scene, os.path.abspath(a.render))
        print("SKINBAKE_CENTER " + " ".join(f"{x:.6f}" for x in mean))


# ------------------------------------------------------------------ add-on

try:
    from bpy_extras.io_utils import ImportHelper
except ImportError:             # pragma: no cover - outside Blender
    ImportHelper = object


class IMPORT_OT_skinbake(bpy.types.Operator, ImportHelper):
    """Import a skinbake image set (select its manifest.json)"""
    bl_idname = "import_scene.skinbake"
    bl_label = "Import skinbake image set"
    bl_options = {"REGISTER", "UNDO"}
    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="manifest.json", options={"HIDDEN"})
    mode: bpy.props.EnumProperty(
        name="Mode",
        items=(("GENERAL", "General", "Principled BSDF with subsurface: any lights"),
               ("EXACT", "Exact (one sun)", "Baked BRDF table for the scene's sun (or the manifest's)"),
               ("BOTH", "Both", "Create both materials")),
        default="GENERAL")
    uv_size: bpy.props.FloatProperty(name="UV size [m]", default=0.1, min=1e-4,
                                     description="Metres covered by one UV unit (tiles the detail maps)")
    detail: bpy.props.BoolProperty(name="Detail normal map", default=True)

    def execute(self, context):
        try:
            m = read_manifest(os.path.dirname(self.filepath))
            mats = []
            if self.mode in ("GENERAL", "BOTH"):
                mats.append(build_general(m, uv_size_m=self.uv_size, no_detail=not self.detail,
                                          unit_scale=context.scene.unit_settings.scale_length or 1.0))
            if self.mode in ("EXACT", "BOTH"):
                mats.append(build_exact(m, sun_dir=scene_sun_direction(context.scene),
                                        uv_size_m=self.uv_size, no_detail=not self.detail))
        except ImageSetError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        for ob in context.selected_objects:
            if ob.type == "MESH":
                if ob.data.materials:
                    ob.data.materials[0] = mats[0]
                else:
                    ob.data.materials.append(mats[0])
        self.report({"INFO"}, "skinbake: " + ", ".join(x.name for x in mats))
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
    except ImageSetError as e:
        print(f"import_skin.py: error: {e}", file=sys.stderr)
        sys.exit(2)
