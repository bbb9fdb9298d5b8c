"""Lights and camera from an exported scene: scene.json of `skinbake scene` (docs/scene-json.md),
so that a Blender render is lit and framed as the POV-Ray export of the same scene file.

Frames and units: scene.json is POV-Ray's left-handed y-up frame in scene units; Blender is
right-handed z-up in metres, so a point (x, y, z) becomes (x, z, y) * unit_mm / 1000 (divided by
the scene's unit scale).  The swap mirrors, which also turns the frame right-handed.
Brightness: a parallel light becomes a sun of strength irradiance_rgb [W/m^2], as the manifest's
sun; POV-Ray's pixel is pi x radiance (a white Lambertian shows irradiance_rgb), Blender's is the
radiance, so Blender's pixels are POV-Ray's / pi (as Mitsuba's).  Point lights in scene files do
not fade with distance; Blender's fall off as 1/d^2 (Cycles: E = P / (4 pi d^2)), so a point
light's power is 4 pi E d^2 with d its distance to the camera's look_at: exact there.
An area light (area_size, a disc facing each shaded point in POV-Ray) becomes a point lamp of that
diameter (a sphere, which every point also sees as a disc) or a sun of the angle the disc
subtends from the look_at.  The background is not a light in POV-Ray (no radiosity), so the world
is left as it is."""
import math
import os

import bpy

from .common import PREFIX, SkinbakeError, json_load, say

FORMAT = "skinbake-scene"
VERSIONS = (1,)


def _vec(v, where):
    if not (isinstance(v, list) and len(v) == 3 and all(isinstance(x, (int, float)) and math.isfinite(x)
                                                         for x in v)):
        raise SkinbakeError(f"scene.json: {where} = {v!r} is not 3 finite numbers")
    return [float(x) for x in v]


def _num(d, key, where, lo, hi):
    v = d.get(key)
    if not (isinstance(v, (int, float)) and math.isfinite(v) and lo <= v <= hi):
        raise SkinbakeError(f"scene.json: {where}.{key} = {v!r} is out of range [{lo:g}, {hi:g}]")
    return float(v)


def read_scene_json(path):
    """The scene of PATH (scene.json, or a directory holding one), checked as far as the importer
    uses it: format, version, image size, camera and lights."""
    if os.path.isdir(path):
        path = os.path.join(path, "scene.json")
    try:
        with open(path) as f:
            sc = json_load(f)
    except OSError as e:
        raise SkinbakeError(f"scene.json: cannot read {path}: {e.strerror}")
    except ValueError as e:
        raise SkinbakeError(f"scene.json: {path} is not JSON ({e})")
    if not isinstance(sc, dict) or sc.get("format") != FORMAT:
        raise SkinbakeError(f"scene.json: {path} is not a skinbake scene (format is not \"{FORMAT}\")")
    if sc.get("version") not in VERSIONS:
        raise SkinbakeError(f"scene.json: version = {sc.get('version')!r} is not one this importer reads "
                            f"({', '.join(map(str, VERSIONS))})")
    for k in ("width_px", "height_px"):
        _num(sc, k, "scene", 1, 16384)
    _num(sc, "unit_mm", "scene", 1e-6, 1e9)
    cam = sc.get("camera")
    if not isinstance(cam, dict) or cam.get("type") not in ("perspective", "orthographic"):
        raise SkinbakeError("scene.json: camera.type is not perspective or orthographic")
    _vec(cam.get("location"), "camera.location")
    _vec(cam.get("look_at"), "camera.look_at")
    if cam["type"] == "perspective":
        _num(cam, "horizontal_fov_deg", "camera", 1e-3, 179.9)
    else:
        _num(cam, "width", "camera", 1e-9, 1e12)
    lights = sc.get("lights")
    if not isinstance(lights, list):
        raise SkinbakeError("scene.json: lights is not a list")
    for i, L in enumerate(lights):
        w = f"lights[{i}]"
        if not isinstance(L, dict) or L.get("type") not in ("parallel", "point"):
            raise SkinbakeError(f"scene.json: {w}.type is not parallel or point")
        _vec(L.get("position"), w + ".position")
        if min(_vec(L.get("irradiance_rgb"), w + ".irradiance_rgb")) < 0:
            raise SkinbakeError(f"scene.json: {w}.irradiance_rgb = {L['irradiance_rgb']} has a value below 0")
        if L["type"] == "parallel":
            _vec(L.get("direction"), w + ".direction")
        _num(L, "area_size", w, 0.0, 1e12)
    sc["_path"] = os.path.abspath(path)
    return sc


def _blender_point(p, scale):
    """A scene.json point [units] in Blender's frame [Blender units]."""
    from mathutils import Vector
    return Vector((p[0], p[2], p[1])) * scale


def _energy_colour(rgb, factor):
    """(strength, colour) of a lamp whose colour times strength is rgb * factor."""
    top = max(rgb)
    if top <= 0:
        return 0.0, (1.0, 1.0, 1.0)
    return top * factor, tuple(c / top for c in rgb)


def apply_scene_json(sc, scene, res=None):
    """Add sc's camera (made the scene's camera) and lights to SCENE in a collection of their own,
    and set the image size (sc's, or width RES with sc's aspect).  Returns the new objects."""
    from mathutils import Vector
    scale = sc["unit_mm"] / 1000.0 / (scene.unit_settings.scale_length or 1.0)
    coll = bpy.data.collections.new(PREFIX + " scene " + os.path.basename(os.path.dirname(sc["_path"])))
    scene.collection.children.link(coll)
    cam = sc["camera"]
    loc = _blender_point(cam["location"], scale)
    target = _blender_point(cam["look_at"], scale)
    cd = bpy.data.cameras.new(PREFIX + " camera")
    cd.sensor_fit = "HORIZONTAL"
    if cam["type"] == "perspective":
        cd.type = "PERSP"
        cd.angle = math.radians(cam["horizontal_fov_deg"])
    else:
        cd.type = "ORTHO"
        cd.ortho_scale = cam["width"] * scale
    dist = (target - loc).length
    cd.clip_start = min(cd.clip_start, dist * 1e-3)
    cd.clip_end = max(cd.clip_end, dist * 1e3)
    co = bpy.data.objects.new(PREFIX + " camera", cd)
    coll.objects.link(co)
    co.location = loc
    co.rotation_euler = (target - loc).to_track_quat("-Z", "Y").to_euler()    # sky: scene +y = Blender +z
    scene.camera = co
    w, h = sc["width_px"], sc["height_px"]
    if res:
        w, h = res, max(1, round(res * h / w))
    scene.render.resolution_x, scene.render.resolution_y = w, h
    scene.render.resolution_percentage = 100
    made = [co]
    for L in sc["lights"]:
        name = f"{PREFIX} light {L.get('name', len(made))}"
        size = L.get("area_size", 0.0) * scale
        if L["type"] == "parallel":
            ld = bpy.data.lights.new(name, "SUN")
            ld.energy, ld.color = _energy_colour(L["irradiance_rgb"], 1.0)
            far = (_blender_point(L["position"], scale) - target).length
            ld.angle = 2.0 * math.atan(0.5 * size / far) if size > 0 and far > 0 else 0.0
            lo = bpy.data.objects.new(name, ld)
            d = Vector(L["direction"])
            lo.rotation_euler = (-Vector((d[0], d[2], d[1]))).to_track_quat("Z", "Y").to_euler()
        else:
            ld = bpy.data.lights.new(name, "POINT")
            p = _blender_point(L["position"], scale)
            d2 = (p - target).length_squared
            ld.energy, ld.color = _energy_colour(L["irradiance_rgb"], 4.0 * math.pi * d2)
            ld.shadow_soft_size = 0.5 * size
            lo = bpy.data.objects.new(name, ld)
            lo.location = p
        coll.objects.link(lo)
        made.append(lo)
    others = [o.name for o in scene.objects if o.type == "LIGHT" and o not in made and not o.hide_render]
    say(f"camera and {len(sc['lights'])} light(s) from {sc['_path']}"
        + (f"; the file's own lamps stay: {', '.join(others)}" if others else ""))
    return made
