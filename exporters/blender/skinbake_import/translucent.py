"""The translucent image set (`skinbake export blender --mode translucent`, docs/translucency.md):
Cycles' Subsurface Scattering node, fitted by the exporter to the bake's Rd(r), added to the
material the importer built.  The set's brdf_lut.exr (and the general mode's fit) already hold
the rest of the baked BRDF: the table minus the node's far field, which is Lambertian with
albedo = the node's colour in Cycles (measured), so material = rest + node.  The node is lit by
each lamp in the view layer that renders that lamp, so the exact mode's per-lamp layers count
every lamp once."""
from .common import ImageSetError, say


def check_version(t):
    """The fit holds for the Cycles it was calibrated on: refuse another Blender (major.minor) rather
    than build a wrong material (Blender 5.0.1 rendered the 3.4.1 fit 12 % dark on the flat box)."""
    import bpy
    want = str(t.get("version", "?"))
    have = "%d.%d" % tuple(bpy.app.version[:2])
    if want.split(".")[:2] != have.split("."):
        raise ImageSetError(f"manifest.json: translucent.version = {want!r}: the subsurface node was fitted to the "
                            f"calibration of Cycles {want}, and this is Blender {bpy.app.version_string}, whose random "
                            "walk answers differently (5.0.1: 12 % darker); use the exact or general set, or "
                            "calibrate this Blender (`make calibrate`)")


def add_subsurface(mat, m, unit_scale=1.0):
    """Add the fitted node beside the shader that reaches MAT's output, when the manifest M has a
    "translucent" section; returns MAT.  UNIT_SCALE: metres per scene unit."""
    t = m.get("translucent")
    if not t:
        return mat
    for key, n in (("colour", 3), ("radius_m", 3)):
        v = t.get(key)
        if not isinstance(v, list) or len(v) != n or not all(isinstance(x, (int, float)) and x > 0 for x in v):
            raise ImageSetError(f"manifest.json: translucent.{key} = {v!r} must be {n} positive numbers")
    check_version(t)
    nt = mat.node_tree
    out = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeOutputMaterial" and n.is_active_output)
    link = out.inputs["Surface"].links[0]
    src = link.from_socket
    nt.links.remove(link)
    ss = nt.nodes.new("ShaderNodeSubsurfaceScattering")
    ss.label = "skinbake: subsurface fitted to Rd(r) (%s %s)" % (t.get("renderer", "?"), t.get("version", "?"))
    falloffs = [i.identifier for i in ss.bl_rna.properties["falloff"].enum_items]
    ss.falloff = t.get("falloff", "RANDOM_WALK") if t.get("falloff") in falloffs else "RANDOM_WALK"
    ss.inputs["Color"].default_value = (*t["colour"], 1.0)
    ss.inputs["Scale"].default_value = float(t.get("scale", 1.0))
    ss.inputs["Radius"].default_value = [r / unit_scale for r in t["radius_m"]]
    if "IOR" in ss.inputs:                  # the calibration's index: the walk depends on it
        ss.inputs["IOR"].default_value = float(t.get("ior", 1.4))
    add = nt.nodes.new("ShaderNodeAddShader")
    add.label = "rest of the table + subsurface"
    ss.location = (out.location[0] - 200, out.location[1] - 300)
    add.location = (out.location[0] - 100, out.location[1])
    out.location = (out.location[0] + 150, out.location[1])
    nt.links.new(src, add.inputs[0])
    nt.links.new(ss.outputs["BSSRDF"], add.inputs[1])
    nt.links.new(add.outputs["Shader"], out.inputs["Surface"])
    mat["skinbake_translucent"] = 1
    say("translucent: Cycles subsurface colour " + " ".join(f"{x:.4g}" for x in t["colour"]) + ", radius " +
        " ".join(f"{x * 1e3:.4g}" for x in t["radius_m"]) + " mm beside the rest of the table")
    return mat
