"""The local thickness from Cycles' Ambient Occlusion node with Inside (docs/translucency.md, What
is left: the plan of a thickness-aware subsurface weight).  A closed slab d thick, seen from
above, shows AO = (d / D)^2 for d < D: the cosine-weighted inward rays that travel D without
meeting the far face are those with cos < d / D.  Renders slabs of 1, 2, 4 and 8 mm with an
emission of the AO factor and prints the mean over pixels and the thickness D sqrt(AO).

    blender -b --factory-startup -noaudio --python scripts/ao_thickness.py
"""
import bpy

D = 0.008                               # AO distance [m]
for d_mm in (1, 2, 4, 8):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    sc.cycles.samples = 64
    sc.cycles.device = "CPU"
    sc.cycles.use_denoising = False
    sc.render.resolution_x = sc.render.resolution_y = 16
    sc.view_settings.view_transform = "Standard"
    bpy.ops.mesh.primitive_cube_add(size=1.0)
    o = bpy.context.active_object
    o.scale = (0.06, 0.06, d_mm * 1e-3)
    bpy.ops.object.transform_apply(scale=True)
    m = bpy.data.materials.new("ao")
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    ao = nt.nodes.new("ShaderNodeAmbientOcclusion")
    ao.inside, ao.only_local, ao.samples = True, True, 16
    ao.inputs["Distance"].default_value = D
    em = nt.nodes.new("ShaderNodeEmission")
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(ao.outputs["AO"], em.inputs["Color"])
    nt.links.new(em.outputs[0], out.inputs["Surface"])
    o.data.materials.append(m)
    cd = bpy.data.cameras.new("c")
    cd.type, cd.ortho_scale = "ORTHO", 0.01
    cam = bpy.data.objects.new("c", cd)
    sc.collection.objects.link(cam)
    cam.location = (0, 0, 0.5)
    sc.camera = cam
    sc.render.image_settings.file_format = "OPEN_EXR"
    sc.render.filepath = bpy.app.tempdir + "ao.exr"
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(sc.render.filepath)
    px = list(img.pixels)
    v = sum(px[0::4]) / (len(px) // 4)
    print("AO_THICKNESS d=%d mm AO=%.4f (d/D)^2=%.4f thickness %.2f mm"
          % (d_mm, v, min(1.0, (d_mm * 1e-3 / D) ** 2), 1e3 * D * v ** 0.5))
