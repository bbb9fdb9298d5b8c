"""skinbake_import: import a skinbake image set (`skinbake export blender`) into Blender.

Works as an extension (Blender 4.2+, blender_manifest.toml), as a legacy add-on (bl_info, Blender
3.x and 4.x) and from the command line through import_skin.py beside this package:

  blender -b my.blend --python-exit-code 1 --python exporters/blender/import_skin.py -- SET \\
      --objects Head,Body --mode exact --save out.blend
  blender -b --factory-startup --python-exit-code 1 --python exporters/blender/import_skin.py -- SET \\
      --mode general --render sphere.png                   # demo sphere, camera and sun

Two material modes:
  general  Principled BSDF (random-walk subsurface, index, roughness, normal map); with a fit in
           the manifest (format 1, "general_fit"), a mixture of closures whose view-dependent
           weights reproduce the baked BRDF.  Any lights, Cycles and EEVEE.
  exact    The baked BRDF itself for every sun, point and spot lamp: one view layer per lamp
           (the other lamps excluded), the lamp's direction or position stored in the layer and
           read with an Attribute node (type View Layer), a Diffuse BSDF whose colour is pi * f_r
           from brdf_lut.exr at that layer's cos(light), cos(view) and delta_phi per shading
           point, and the compositor summing the layers.  Cycles' diffuse closure returns
           colour/pi * E * cos_l, so each lamp gives exactly E cos_l f_r; its falloff, cone and
           shadows stay Cycles' job.  World light and area lamps are shaded by the general
           material in one more view layer.
Blender's SVM shader nodes see no light direction (and Debian's build has no OSL), which is why
the exact mode needs a view layer per lamp.  Node inputs are looked up by their Blender 3.x and
4.x names.  Errors in the image set, a missing object or an object without UVs raise
SkinbakeError; on the command line they print "import_skin.py: error: ..." and exit with status 2.

One module per concept: schema (the manifest's keys and ranges), imagefiles (EXR/PNG structure),
imageset (reading and checking a set, loading its images), nodes, detail, calibration, footprint
(the pixel's width, for Cycles 4.2-4.3's subsurface fall-back), general and exact (the materials),
objects, layers (lights and view layers), compositor, scene (demo scene and render), scenejson
(camera and lights from skinbake's scene.json), importer, cli, ui (the add-on's operator).
"""
bl_info = {
    "name": "skinbake image set",
    "author": "skinbake",
    "version": (1, 1, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > skinbake image set (manifest.json)",
    "description": "Skin materials from a skinbake image set (general Principled fit, or exact per lamp)",
    "category": "Import-Export",
}

from .common import PREFIX, ImageSetError, SkinbakeError, say  # noqa: E402
from .schema import FAMILY_FILES, FILES, FORMAT, FORMAT_VERSIONS, VERSION as __version__  # noqa: E402
from .imagefiles import check_exr, check_png  # noqa: E402
from .imageset import load_family_image, load_image, read_manifest  # noqa: E402
from .calibration import albedo_factor as albedo_calibration  # noqa: E402
from .general import build_general  # noqa: E402
from .exact import build_exact  # noqa: E402
from .objects import assign, find_objects, generate_uvs, measure_uv_size, prepare_objects  # noqa: E402
from .layers import setup_exact_layers, world_is_dark  # noqa: E402
from .scene import build_scene, centre_mean, fix_denoiser, render, render_settings  # noqa: E402
from .scenejson import apply_scene_json, read_scene_json  # noqa: E402
from .importer import import_set  # noqa: E402
from .cli import main, run  # noqa: E402
from .ui import IMPORT_OT_skinbake, register, unregister  # noqa: E402

__all__ = ["PREFIX", "ImageSetError", "SkinbakeError", "say", "FAMILY_FILES", "FILES", "FORMAT", "FORMAT_VERSIONS",
           "check_exr", "check_png", "load_family_image", "load_image", "read_manifest", "albedo_calibration",
           "build_general", "build_exact", "assign", "find_objects", "generate_uvs", "measure_uv_size",
           "prepare_objects", "setup_exact_layers", "world_is_dark", "build_scene", "centre_mean", "fix_denoiser",
           "render", "render_settings", "apply_scene_json", "read_scene_json", "import_set", "main", "run", "IMPORT_OT_skinbake", "register", "unregister"]
