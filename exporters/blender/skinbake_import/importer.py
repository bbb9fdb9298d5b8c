"""Importing an image set: what the command line and the add-on both do."""
import bpy

from .exact import build_exact
from .general import build_general
from .layers import setup_exact_layers
from .objects import assign, prepare_objects
from .common import say
from .scene import fix_denoiser
from .translucent import add_subsurface


def import_set(m, scene, obs, mode, no_detail=False, no_specular=False, calibrate=True, uv_size=None,
               gen_uvs=False, engine=None):
    """Everything the command line and the add-on do: materials onto OBS, and for the exact mode
    the per-lamp view layers.  Returns the material."""
    unit = scene.unit_settings.scale_length or 1.0
    prepare_objects(obs, m, mode, no_detail, uv_size, gen_uvs, unit)
    kw = dict(no_detail=no_detail, no_specular=no_specular, unit_scale=unit, calibrate=calibrate)
    mat = build_exact(m, **kw) if mode == "exact" else build_general(m, **kw)
    mat = add_subsurface(mat, m, unit)          # a translucent set: the node beside the rest
    assign(obs, mat)
    say(f"material '{mat.name}'" + (f" on {', '.join(repr(o.name) for o in obs)}" if obs else
                                     " (not assigned: no --objects)"))
    if mode == "exact":
        setup_exact_layers(scene, bpy.context.view_layer, engine)
    fix_denoiser(scene)
    return mat
