"""Render settings, the demo scene (an object, an orthographic camera, the manifest's sun) and
rendering with the result read back from the file."""
import math

import bpy

from .common import say


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


def _direction(elev_deg, azim_deg):
    e, a = math.radians(elev_deg), math.radians(azim_deg)
    return (math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e))


def engine_id(name):
    """The identifier this Blender gives engine NAME: EEVEE is BLENDER_EEVEE_NEXT in 4.2-4.5."""
    if name == "BLENDER_EEVEE" and (4, 2, 0) <= bpy.app.version < (5, 0, 0):
        return "BLENDER_EEVEE_NEXT"
    return name


def is_eevee(engine):
    return engine in ("BLENDER_EEVEE", "BLENDER_EEVEE_NEXT")


def render_settings(scene, res=None, samples=None, engine=None):
    """Cycles CPU (or EEVEE), fixed seed, denoiser off, Standard view transform."""
    if engine:
        scene.render.engine = engine_id(engine)
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
