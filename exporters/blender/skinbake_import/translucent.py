"""The translucent image set (`skinbake export blender --mode translucent`, docs/translucency.md):
Cycles' Subsurface Scattering node, fitted by the exporter to the bake's Rd(r), added to the
material the importer built.  The manifest's "translucent" section holds one fit per Blender
version calibrated (versions[]: Debian's 3.4 "Random Walk", 4.5 and 5.0 "Random Walk (Skin)");
the importer takes its own Blender's (major.minor).  The set's brdf_lut.exr (and the general
mode's fit) hold the rest of the baked BRDF: the table minus the largest of the nodes' far fields
(measured: none depends on theta_i; 3.4's is Lambertian, 4.5's and 5.0's rise toward grazing
view), so material = rest + node + a Diffuse BSDF whose colour is lambert_extra (that largest far
field minus this version's) at the view angle (translucent.theta_o_deg).  The node is lit by each
lamp in the view layer that renders that lamp, so the exact mode's per-lamp layers count every
lamp once.  A family set (`--family --maps`) gives each version's node colour and radius per texel
(versions[].maps: sss_colour_M.N.exr, sss_radius_M.N.exr) and lambert_extra per sub-grid point
(sss_extra_M.N.exr, blended as family_lut.exr is)."""
import math
import os

from .common import ImageSetError, say


def pick_version(t, family=True):
    """The versions[] entry of this Blender (major.minor).  Another Blender's fit is never used:
    the walk answers differently per version (5.0.1 rendered the 3.4.1 fit 12 % dark on the flat
    box, its "Random Walk" being 3.4's fixed-radius walk).  Without a fit for this Blender: None
    for a single bake's set (FAMILY false: the importer falls back to the far field as a diffuse,
    far_field_fallback), refused for a family set."""
    import bpy
    have = "%d.%d" % tuple(bpy.app.version[:2])
    vs = t.get("versions")
    if not isinstance(vs, list) or not vs or not all(isinstance(v, dict) for v in vs):
        raise ImageSetError(f"manifest.json: translucent.versions = {vs!r} must be a list of fits, "
                            "one per Blender version (export the set again with this skinbake)")
    for v in vs:
        if v.get("blender") == have:
            return v
    if not family:
        return None
    got = ", ".join(repr(v.get("blender")) for v in vs)
    raise ImageSetError(f"manifest.json: translucent.versions has fits for Blender {got}, not for "
                        f"this Blender {bpy.app.version_string} ({have}): its random walk was not "
                        "calibrated, so the node cannot be fitted; use the exact or general set "
                        "(export with `--mode exact`), or calibrate this Blender (`make "
                        "calibrate-blender` with its bpy) and export again")


def view_colour(nt, sock, views, rgb):
    """SOCK's colour: RGB[k] at view angle VIEWS[k] [deg], linear in cos(theta_o) between them (a
    Color Ramp on Incoming . Normal); a constant when all are equal."""
    if all(e == rgb[0] for e in rgb):
        sock.default_value = (*rgb[0], 1.0)
        return
    geo = nt.nodes.new("ShaderNodeNewGeometry")
    dot = nt.nodes.new("ShaderNodeVectorMath")
    dot.operation = "DOT_PRODUCT"
    nt.links.new(geo.outputs["Incoming"], dot.inputs[0])
    nt.links.new(geo.outputs["Normal"], dot.inputs[1])
    ramp = nt.nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.interpolation = "LINEAR"
    stops = sorted((math.cos(math.radians(a)), e) for a, e in zip(views, rgb))
    els = ramp.color_ramp.elements
    while len(els) < len(stops):
        els.new(0.5)
    for el, (pos, e) in zip(els, stops):
        el.position = pos
        el.color = (*e, 1.0)
    nt.links.new(dot.outputs["Value"], ramp.inputs["Fac"])
    nt.links.new(ramp.outputs["Color"], sock)


def _maps_image(m, maps, key, where, size):
    """One per-texel file of a family set's translucent maps (float EXR, checked as the family's
    own files are), at SIZE (width, height)."""
    from .imagefiles import check_exr
    from .imageset import load_image
    e = maps.get(key)
    if not isinstance(e, dict) or not isinstance(e.get("file"), str) or \
            os.path.basename(e["file"]) != e["file"] or (e.get("width"), e.get("height")) != size:
        raise ImageSetError(f"{where}.maps.{key} = {e!r} must name a file of the set of "
                            f"{size[0]}x{size[1]} px")
    p = os.path.join(m["_dir"], e["file"])
    if not os.path.isfile(p) or os.path.getsize(p) == 0:
        raise ImageSetError(f"{p}: missing or empty (listed in manifest.json as {where}.maps.{key})")
    check_exr(p, *size)
    img = load_image({"files": {key: dict(e, path=e["file"])}, "_dir": m["_dir"]}, key)
    if hasattr(img, "use_half_precision"):
        img.use_half_precision = False
    return img


def _family_extra(tr, m, img, views, x0, y0):
    """lambert_extra of the texel: sss_extra_M.N.exr holds it per sub-grid point (row = slice)
    and view node (column k at VIEWS[k]); linear in cos(theta_o) between the columns, blended
    over the texel's neighbouring sub-grid points as family_lut is (exact.family_corners)."""
    from .exact import family_corners
    n = len(views)
    geo = tr.node("ShaderNodeNewGeometry", (x0, y0))
    cosv = tr.vmath("DOT_PRODUCT", geo.outputs["Incoming"], geo.outputs["Normal"], (x0 + 150, y0))
    ramp = tr.node("ShaderNodeValToRGB", (x0 + 300, y0), "view node index (from cos theta_o)")
    ramp.color_ramp.interpolation = "LINEAR"
    stops = sorted((math.cos(math.radians(a)), k / (n - 1)) for k, a in enumerate(views))
    els = ramp.color_ramp.elements
    while len(els) < len(stops):
        els.new(0.5)
    for el, (pos, f) in zip(els, stops):
        el.position = pos
        el.color = (f, f, f, f)
    tr.link(cosv, ramp.inputs["Fac"])
    p = tr.math("MULTIPLY", ramp.outputs["Alpha"], n - 1, loc=(x0 + 600, y0))
    k0 = tr.math("MINIMUM", tr.math("FLOOR", p, loc=(x0 + 750, y0)), n - 2, loc=(x0 + 900, y0))
    fk = tr.math("SUBTRACT", p, k0, loc=(x0 + 1050, y0))
    u0 = tr.math("DIVIDE", tr.math("ADD", k0, 0.5, loc=(x0 + 1050, y0 - 150)), n, loc=(x0 + 1200, y0 - 150))
    slices, blend = family_corners(tr, m, x0, y0 - 600)
    ns = m["family"]["slices"]
    cols = []
    for corner, sl in enumerate(slices):
        v = tr.math("DIVIDE", tr.math("ADD", sl, 0.5, loc=(x0 + 1400, y0 - 300 * corner)), ns,
                    loc=(x0 + 1550, y0 - 300 * corner))
        pair = []
        for dk in (0, 1):
            u = tr.math("ADD", u0, dk / n, loc=(x0 + 1700, y0 - 300 * corner - 100 * dk))
            te = tr.tex(img, tr.xyz(u, v, 0.0, (x0 + 1850, y0 - 300 * corner - 100 * dk)),
                        (x0 + 2000, y0 - 300 * corner - 100 * dk), "EXTEND", "sss_extra", interpolation="Closest")
            pair.append(te.outputs["Color"])
        cols.append(tr.mix(pair[0], pair[1], fk, (x0 + 2250, y0 - 300 * corner)))
    return blend(cols, x0 + 2500, y0)


def _family_maps(mat, m, v, where, ss, unit_scale):
    """A family set (`export blender --family --maps --mode translucent`): the node's colour and
    radius per texel (the members' fits interpolated), and lambert_extra per texel; returns the
    socket of the latter."""
    from .nodes import Tree
    maps = v.get("maps")
    if not isinstance(maps, dict):
        raise ImageSetError(f"{where}.maps = {maps!r}: a family set needs the node's per-texel maps "
                            "(export the set again with this skinbake)")
    fc = m["family"]["files"]["family_coord"]
    size = (fc["width"], fc["height"])
    views = m["translucent"]["theta_o_deg"]
    tr = Tree(mat, keep=True)
    x0, y0 = ss.location[0] - 900, ss.location[1] - 400
    uv = tr.node("ShaderNodeTexCoord", (x0 - 300, y0)).outputs["UV"]
    col = tr.tex(_maps_image(m, maps, "colour", where, size), uv, (x0, y0), "EXTEND",
                 maps["colour"]["file"] + " (per texel)")
    tr.link(col.outputs["Color"], ss.inputs["Color"])
    rad = tr.tex(_maps_image(m, maps, "radius_m", where, size), uv, (x0, y0 - 300), "EXTEND",
                 maps["radius_m"]["file"] + " (per texel, m)")
    tr.link(tr.vmath("SCALE", rad.outputs["Color"], loc=(x0 + 300, y0 - 300), scale=1.0 / unit_scale),
            ss.inputs["Radius"])
    extra = _maps_image(m, maps, "extra", where, (len(views), m["family"]["slices"]))
    return _family_extra(tr, m, extra, views, x0 - 2800, y0 - 900)


def _node_any(nt, *names):
    """A new node of the first type in NAMES this Blender has (3.x and 4.x names)."""
    for n in names:
        try:
            return nt.nodes.new(n)
        except RuntimeError:
            continue
    raise ImageSetError("this Blender has none of the nodes " + ", ".join(names))


def check_thickness(th, where):
    """The version entry's "thickness" section (export/blender/blender_sss_thick.h): the AO
    distance, thickness nodes ascending in (0, ao_distance_m], one weight per node and channel in
    [0, 1], the last 1."""
    d, w, dist, near = th.get("d_m"), th.get("weight"), th.get("ao_distance_m"), th.get("ao_near_m")
    if not isinstance(dist, (int, float)) or not 0 < dist < 1 or not isinstance(near, (int, float)) \
            or not 0 < near < dist or not isinstance(d, list) or len(d) < 2 \
            or not all(isinstance(x, (int, float)) and 0 < x <= dist for x in d) \
            or any(b <= a for a, b in zip(d, d[1:])):
        raise ImageSetError(f"{where}.thickness: ao_distance_m = {dist!r}, ao_near_m = {near!r} and "
                            f"d_m = {d!r} must be distances in metres (near the shorter) and "
                            "thicknesses ascending up to ao_distance_m")
    if not isinstance(w, list) or len(w) != len(d) or not all(
            isinstance(e, list) and len(e) == 3 and all(isinstance(y, (int, float)) and 0 <= y <= 1
                                                        for y in e) for e in w):
        raise ImageSetError(f"{where}.thickness.weight = {w!r} must be one [R, G, B] in [0, 1] per d_m")


def thickness_shader(nt, v, views, unit_scale, loc):
    """The node weighted by the local thickness (docs/translucency.md, Back light): per channel
    times its weight f_c(d) (the node times min_c f_c, and per channel a node of that channel
    alone, colour and radius 0 elsewhere, times f_c - min f; Mix Shaders with nothing), and a Diffuse BSDF of (1 - f) times the node's own far field, so that a
    flat surface under uniform light still gets the node's far field in full.  d is the local
    thickness from the Ambient Occlusion node with Inside (within D a slab d thick leaves
    (d / D)^2 of the cosine-weighted inward rays unoccluded); f_c is linear
    in d between thickness.d_m (an RGB Curves node).  The thickness comes from two AO nodes: one
    within ao_near_m for thin parts (with one within 8 mm alone a 1 mm slab leaves 1/64 of the
    rays unoccluded, 0 or 1 of 16, and the weight, not linear in that count, came out biased),
    and beyond it one within ao_distance_m; the curve's coordinate is linear in each AO.
    Returns the output socket."""
    th = v["thickness"]
    dist, near = th["ao_distance_m"], th["ao_near_m"]
    q = (near / dist) ** 2
    x0, y0 = loc

    def coord(d):
        """The curve's coordinate of thickness d: 0.5 (d / near)^2 up to near, then from 0.5
        to 1 linear in (d / dist)^2."""
        return 0.5 * (d / near) ** 2 if d <= near else 0.5 + 0.5 * ((d / dist) ** 2 - q) / (1 - q)

    def math(op, a, b, at, clamp=False):
        n = nt.nodes.new("ShaderNodeMath")
        n.operation, n.location, n.use_clamp = op, at, clamp
        for k, x in enumerate((a, b)):
            if isinstance(x, (int, float)):
                n.inputs[k].default_value = x
            else:
                nt.links.new(x, n.inputs[k])
        return n.outputs[0]

    aos = []
    for k, dd in enumerate((near, dist)):
        ao = nt.nodes.new("ShaderNodeAmbientOcclusion")
        ao.location = (x0 - 1500, y0 - 200 * k)
        ao.inside, ao.only_local, ao.samples = True, True, 16
        ao.inputs["Distance"].default_value = dd / unit_scale
        aos.append(ao.outputs["AO"])
    # Beyond near (the near AO sees nothing: 1), the far AO's share, 0..1.
    far = math("MULTIPLY", math("SUBTRACT", aos[1], q, (x0 - 1300, y0 - 200)), 1 / (1 - q),
               (x0 - 1150, y0 - 200), clamp=True)
    beyond = math("GREATER_THAN", aos[0], 0.9999, (x0 - 1300, y0))
    xsock = math("MULTIPLY", math("ADD", aos[0], math("MULTIPLY", far, beyond, (x0 - 1000, y0 - 100)),
                                  (x0 - 900, y0)), 0.5, (x0 - 800, y0))
    cmb = _node_any(nt, "ShaderNodeCombineColor", "ShaderNodeCombineRGB")
    cmb.location = (x0 - 850, y0)
    for i in range(3):
        nt.links.new(xsock, cmb.inputs[i])
    cur = nt.nodes.new("ShaderNodeRGBCurve")
    cur.label = "skinbake: subsurface weight per channel over the thickness coordinate"
    cur.location = (x0 - 650, y0)
    mp = cur.mapping
    mp.use_clip = True
    for c in range(4):
        pts = [(0.0, th["weight"][0][c] if c < 3 else 0.0)] + \
            [(coord(d), w[c] if c < 3 else 0.0) for d, w in zip(th["d_m"], th["weight"])]
        if c == 3:
            pts = [(0.0, 0.0), (1.0, 1.0)]
        cv = mp.curves[c]
        while len(cv.points) < len(pts):
            cv.points.new(0.5, 0.5)
        for p, (x, y) in zip(cv.points, pts):
            p.location = (x, y)
            p.handle_type = "VECTOR"
    mp.update()
    nt.links.new(cmb.outputs[0], cur.inputs["Color"])
    sep = _node_any(nt, "ShaderNodeSeparateColor", "ShaderNodeSeparateRGB")
    sep.location = (x0 - 450, y0)
    nt.links.new(cur.outputs["Color"], sep.inputs[0])
    # The node in full times the smallest weight, and per channel a node of that channel alone
    # times the rest of its weight: where every weight is 1 (thick parts, the flat box) the
    # material is the unweighted node, sampled as before (one node per channel alone left the
    # blue node a seventh of the picks: the flat box's blue went from +0.8 % to +1.5 %).
    low = math("MINIMUM", math("MINIMUM", sep.outputs[0], sep.outputs[1], (x0 - 300, y0 - 100)),
               sep.outputs[2], (x0 - 200, y0 - 100))
    out = None
    for c in range(4):
        ss = nt.nodes.new("ShaderNodeSubsurfaceScattering")
        ss.label = "skinbake: subsurface" + (", %s channel" % "RGB"[c] if c < 3 else "")
        ss.location = (x0 - 300, y0 - 250 * (c + 1))
        ss.falloff = v["falloff"]
        ss.inputs["Color"].default_value = tuple(v["colour"][k] if c in (k, 3) else 0.0 for k in range(3)) + (1.0,)
        ss.inputs["Scale"].default_value = float(v.get("scale", 1.0))
        ss.inputs["Radius"].default_value = [v["radius_m"][k] / unit_scale if c in (k, 3) else 0.0
                                             for k in range(3)]
        if "IOR" in ss.inputs:
            ss.inputs["IOR"].default_value = float(v.get("ior", 1.4))
        mix = nt.nodes.new("ShaderNodeMixShader")
        mix.location = (x0 - 100, y0 - 250 * (c + 1))
        fac = low if c == 3 else math("SUBTRACT", sep.outputs[c], low, (x0 - 200, y0 - 250 * (c + 1)), clamp=True)
        nt.links.new(fac, mix.inputs["Fac"])
        nt.links.new(ss.outputs[0], mix.inputs[2])
        if out is None:
            out = mix.outputs[0]
        else:
            add = nt.nodes.new("ShaderNodeAddShader")
            add.location = (x0 + 50, y0 - 250 * (c + 1))
            nt.links.new(out, add.inputs[0])
            nt.links.new(mix.outputs[0], add.inputs[1])
            out = add.outputs[0]
    inv = nt.nodes.new("ShaderNodeVectorMath")
    inv.operation, inv.location = "SUBTRACT", (x0 - 300, y0 + 200)
    inv.inputs[0].default_value = (1.0, 1.0, 1.0)
    nt.links.new(cur.outputs["Color"], inv.inputs[1])
    mul = nt.nodes.new("ShaderNodeVectorMath")
    mul.operation, mul.location = "MULTIPLY", (x0 - 150, y0 + 200)
    nt.links.new(inv.outputs[0], mul.inputs[0])
    far = v["far_pi_f"]
    if all(e == far[0] for e in far):
        mul.inputs[1].default_value = tuple(far[0])
    else:
        view_colour(nt, mul.inputs[1], views, far)
    dif = nt.nodes.new("ShaderNodeBsdfDiffuse")
    dif.label = "skinbake: (1 - weight) x the node's far field"
    dif.location = (x0, y0 + 200)
    nt.links.new(mul.outputs[0], dif.inputs["Color"])
    add = nt.nodes.new("ShaderNodeAddShader")
    add.location = (x0 + 200, y0)
    nt.links.new(out, add.inputs[0])
    nt.links.new(dif.outputs[0], add.inputs[1])
    return add.outputs[0]


def checked_views(t):
    """translucent.theta_o_deg of the manifest section T: at least 2 angles in [0, 90)."""
    views = t.get("theta_o_deg")
    if not isinstance(views, list) or len(views) < 2 or not all(
            isinstance(y, (int, float)) and 0 <= y < 90 for y in views):
        raise ImageSetError(f"manifest.json: translucent.theta_o_deg = {views!r} must be angles "
                            "in [0, 90) degrees")
    return views


def check_rgb_per_view(x, views, name):
    """X (named NAME in messages) must hold one [R, G, B] in [0, 1] per view."""
    if not isinstance(x, list) or len(x) != len(views) or not all(
            isinstance(e, list) and len(e) == 3 and all(isinstance(y, (int, float)) and 0 <= y <= 1
                                                        for y in e) for e in x):
        raise ImageSetError(f"{name} = {x!r} must be one [R, G, B] in [0, 1] "
                            "per translucent.theta_o_deg")


def detach_surface(nt):
    """The active material output of node tree NT and the socket that fed its Surface, unlinked."""
    out = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeOutputMaterial" and n.is_active_output)
    link = out.inputs["Surface"].links[0]
    src = link.from_socket
    nt.links.remove(link)
    return out, src


def far_field_fallback(mat, t):
    """A single bake's translucent set on a Blender without its own fit: no subsurface node (an
    uncalibrated walk would not match Rd(r)); the far field the set's table lost
    (translucent.far_pi_f_removed, per theta_o_deg) comes back as a Diffuse BSDF beside the rest,
    so flat light sums to the baked BRDF as in the exact set, but no light travels under the
    surface.  Says so; returns MAT."""
    import bpy
    views, far = checked_views(t), t.get("far_pi_f_removed")
    check_rgb_per_view(far, views, "manifest.json: translucent.far_pi_f_removed")
    nt = mat.node_tree
    out, src = detach_surface(nt)
    dif = nt.nodes.new("ShaderNodeBsdfDiffuse")
    dif.label = "skinbake: the subsurface node's far field (no fit for this Blender)"
    dif.location = (out.location[0] - 400, out.location[1] - 300)
    view_colour(nt, dif.inputs["Color"], views, far)
    add = nt.nodes.new("ShaderNodeAddShader")
    add.location = (out.location[0] - 100, out.location[1])
    out.location = (out.location[0] + 150, out.location[1])
    nt.links.new(src, add.inputs[0])
    nt.links.new(dif.outputs["BSDF"], add.inputs[1])
    nt.links.new(add.outputs["Shader"], out.inputs["Surface"])
    mat["skinbake_translucent"] = 0
    got = ", ".join(str(v.get("blender")) for v in t.get("versions", []))
    say(f"translucent: no fit for this Blender {bpy.app.version_string} in the set (fits for "
        f"{got}): no subsurface node, its far field as a diffuse (up to " +
        " ".join(f"{max(e[c] for e in far):.4g}" for c in range(3)) + "), so flat light matches "
        "the bake but no light travels under the surface (calibrate this Blender: make "
        "calibrate-blender with its bpy, and export again)")
    return mat


def add_subsurface(mat, m, unit_scale=1.0):
    """Add the fitted node beside the shader that reaches MAT's output, when the manifest M has a
    "translucent" section; returns MAT.  UNIT_SCALE: metres per scene unit."""
    t = m.get("translucent")
    if not t:
        return mat
    v = pick_version(t, "family" in m)
    if v is None:
        return far_field_fallback(mat, t)
    where = f"manifest.json: translucent.versions[{v.get('blender')}]"
    for key in ("colour", "radius_m"):
        x = v.get(key)
        if not isinstance(x, list) or len(x) != 3 or not all(isinstance(y, (int, float)) and y > 0
                                                             for y in x):
            raise ImageSetError(f"{where}.{key} = {x!r} must be 3 positive numbers")
    views = checked_views(t)
    extra = v.get("lambert_extra")
    check_rgb_per_view(extra, views, f"{where}.lambert_extra")
    nt = mat.node_tree
    out, src = detach_surface(nt)
    ss = nt.nodes.new("ShaderNodeSubsurfaceScattering")
    ss.label = "skinbake: subsurface fitted to Rd(r) (Cycles %s)" % v.get("version", "?")
    falloffs = [i.identifier for i in ss.bl_rna.properties["falloff"].enum_items]
    if v.get("falloff") not in falloffs:
        raise ImageSetError(f"{where}.falloff = {v.get('falloff')!r}: this Blender has "
                            f"{', '.join(falloffs)}")
    ss.falloff = v["falloff"]
    ss.inputs["Color"].default_value = (*v["colour"], 1.0)
    ss.inputs["Scale"].default_value = float(v.get("scale", 1.0))
    ss.inputs["Radius"].default_value = [r / unit_scale for r in v["radius_m"]]
    if "IOR" in ss.inputs:                  # the calibration's index: the walk depends on it
        ss.inputs["IOR"].default_value = float(v.get("ior", 1.4))
    add = nt.nodes.new("ShaderNodeAddShader")
    add.label = "rest of the table + subsurface"
    ss.location = (out.location[0] - 200, out.location[1] - 300)
    add.location = (out.location[0] - 100, out.location[1])
    out.location = (out.location[0] + 150, out.location[1])
    nt.links.new(src, add.inputs[0])
    sock = ss.outputs["BSSRDF"]
    thick = v.get("thickness") if "family" not in m else None
    if thick is not None:                   # the node weighted by the local thickness
        if not isinstance(thick, dict):
            raise ImageSetError(f"{where}.thickness = {thick!r} must be an object")
        check_thickness(thick, where)
        sock = thickness_shader(nt, v, views, unit_scale, (ss.location[0], ss.location[1] - 300))
        nt.nodes.remove(ss)
    fam_extra = _family_maps(mat, m, v, where, ss, unit_scale) if "family" in m else None
    if fam_extra is not None or max(max(e) for e in extra) > 0:   # this version's far field below
        dif = nt.nodes.new("ShaderNodeBsdfDiffuse")                # the one the table lost
        dif.label = "skinbake: far field the other versions' nodes have more"
        dif.location = (out.location[0] - 400, out.location[1] - 500)
        if fam_extra is not None:
            nt.links.new(fam_extra, dif.inputs["Color"])
        else:
            view_colour(nt, dif.inputs["Color"], views, extra)
        add2 = nt.nodes.new("ShaderNodeAddShader")
        add2.location = (out.location[0] - 250, out.location[1] - 350)
        nt.links.new(sock, add2.inputs[0])
        nt.links.new(dif.outputs["BSDF"], add2.inputs[1])
        sock = add2.outputs[0]
    nt.links.new(sock, add.inputs[1])
    nt.links.new(add.outputs["Shader"], out.inputs["Surface"])
    mat["skinbake_translucent"] = 1
    if "family" in m:
        say(f"translucent: Cycles {v.get('version')} subsurface ({v['falloff']}) per texel from "
            f"{v['maps']['colour']['file']} and {v['maps']['radius_m']['file']} beside the rest of the "
            f"family's tables, diffuse from {v['maps']['extra']['file']}")
        return mat
    say(f"translucent: Cycles {v.get('version')} subsurface ({v['falloff']}) colour " +
        " ".join(f"{x:.4g}" for x in v["colour"]) + ", radius " +
        " ".join(f"{x * 1e3:.4g}" for x in v["radius_m"]) + " mm beside the rest of the table" +
        (", weighted by the thickness (AO within %.4g mm)" % (thick["ao_distance_m"] * 1e3)
         if thick is not None else "") +
        (", diffuse up to " + " ".join(f"{max(e[c] for e in extra):.4g}" for c in range(3))
         if max(max(e) for e in extra) > 0 else ""))
    return mat
