"""The pixel footprint, and the subsurface radius that Cycles 4.2 and 4.3 keep as a random walk.

Cycles 4.2's and 4.3's bssrdf_setup (kernel/closure/bssrdf.h, shipped with Blender in
scripts/addons_core/cycles/source) render every channel whose subsurface radius is below a
quarter of the ray's footprint, sd->dP (for a camera ray: the pixel's width at the point), as a
Lambert diffuse of the same colour ("Fall back to diffuse if the radius is smaller than a quarter
pixel"); 3.4, 4.4, 4.5 and 5.0 fall back only below 1e-8.  The general mode's Base Colours are
calibrated for the random walk (calibration.VIEW_RESPONSE: 0.77-1.77 times the Lambert response),
so on such a Blender each channel's radius is raised to MARGIN pixel footprints where it is
smaller: a blur below a third of a pixel, which the pixel filter (1.5 px) hides, for the response
the calibration holds.  The footprint follows the camera: the view distance per shading point
times the pixel's angle, or the orthographic pixel, from drivers on the scene's camera and
resolution (set at import time too, for a scene without a camera)."""
import bpy

from . import calibration
from .common import say

MARGIN = 0.3     # footprints: the quarter pixel plus 20 %

# Pixel width per unit of view distance (perspective) and in scene units (orthographic) of the
# scene's camera: sensor (mm) over lens (mm) or ortho_scale, over the pixels across the fitted
# side (sensor_fit AUTO: the larger side).  Camera type: PERSP 0, ORTHO 1, PANO 2;
# sensor_fit: AUTO 0, HORIZONTAL 1, VERTICAL 2.
_PIXELS = "(max(rx, ry) if fit == 0 else (rx if fit == 1 else ry)) * pc / 100"
_PERSP = f"0 if ty == 1 else (sh if fit == 2 else sw) / ln / ({_PIXELS})"
_ORTHO = f"os / ({_PIXELS}) if ty == 1 else 0"
_VARS = (("rx", "render.resolution_x"), ("ry", "render.resolution_y"),
         ("pc", "render.resolution_percentage"), ("ty", "camera.data.type"),
         ("fit", "camera.data.sensor_fit"), ("sw", "camera.data.sensor_width"),
         ("sh", "camera.data.sensor_height"), ("ln", "camera.data.lens"),
         ("os", "camera.data.ortho_scale"))


def camera_pixel(scene):
    """(pixel width per unit view distance, orthographic pixel width) of SCENE's camera now, as the
    drivers compute them; a 36 mm sensor behind a 50 mm lens at 1920 pixels without a camera."""
    r = scene.render
    cam = scene.camera.data if scene.camera is not None and scene.camera.type == "CAMERA" else None
    if cam is None:
        return 36.0 / 50.0 / 1920.0, 0.0
    fit = ("AUTO", "HORIZONTAL", "VERTICAL").index(cam.sensor_fit)
    px = (max(r.resolution_x, r.resolution_y) if fit == 0 else
          (r.resolution_x if fit == 1 else r.resolution_y)) * r.resolution_percentage / 100.0
    if cam.type == "ORTHO":
        return 0.0, cam.ortho_scale / px
    return (cam.sensor_height if fit == 2 else cam.sensor_width) / cam.lens / px, 0.0


def _driven_value(tr, scene, value, expr, loc, label):
    n = tr.node("ShaderNodeValue", loc, label)
    n.outputs[0].default_value = value
    fc = n.outputs[0].driver_add("default_value")
    d = fc.driver
    d.type = "SCRIPTED"
    for name, path in _VARS:
        v = d.variables.new()
        v.name, v.type = name, "SINGLE_PROP"
        v.targets[0].id_type = "SCENE"
        v.targets[0].id = scene
        v.targets[0].data_path = path
    d.expression = expr
    return n.outputs[0]


def footprint(tr, scene, loc):
    """Socket: the pixel's width at the shading point in scene units, for camera rays."""
    per_m, ortho = camera_pixel(scene)
    kp = _driven_value(tr, scene, per_m, _PERSP, loc, "pixel width per unit distance (driver)")
    ko = _driven_value(tr, scene, ortho, _ORTHO, (loc[0], loc[1] - 120), "orthographic pixel width (driver)")
    cam = tr.node("ShaderNodeCameraData", (loc[0], loc[1] + 160))
    return tr.math("MULTIPLY_ADD", cam.outputs["View Distance"], kp, ko, loc=(loc[0] + 200, loc[1]))


def walk_radius(tr, radius, loc, scene=None):
    """RADIUS (RGB in scene units, or a socket) as the random walk should get it: on a Blender that
    falls back to diffuse below a quarter pixel, max(RADIUS, MARGIN footprints) per channel."""
    if calibration.sss_diffuse_below_pixels() is None:
        return radius
    say(f"Cycles {bpy.app.version_string.split()[0]} renders subsurface radii below "
        f"{calibration.sss_diffuse_below_pixels()} pixel as diffuse: radii kept >= {MARGIN} pixel "
        "(drivers on the scene's camera and resolution)")
    f = footprint(tr, scene or bpy.context.scene, loc)
    low = tr.vmath("SCALE", (MARGIN, MARGIN, MARGIN), loc=(loc[0] + 400, loc[1]), scale=f)
    out = tr.vmath("MAXIMUM", radius, low, loc=(loc[0] + 600, loc[1]))
    out.node.label = f"radius >= {MARGIN} pixel (Cycles {bpy.app.version_string.split()[0]} " \
                     "renders less as diffuse)"
    return out
