"""The exact mode's lights and view layers: one view layer per sun, point and spot lamp (the
other lamps excluded, the lamp stored in the layer's properties), one for the world and area
lamps, summed by the compositor (compositor.py)."""
import math

import bpy

from .common import PREFIX, VL_DIR, VL_EXACT, VL_POINT, VL_POS, SkinbakeError, say
from .compositor import compositor_sum
from .scene import is_eevee


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
    if is_eevee(engine) and lit_world and exact:
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
    compositor_sum(scene, source, made)
    scene[PREFIX + "_exact_layers"] = made
    say(f"exact mode: the compositor sums {len(made)} view layer(s); view layer '{source.name}' is "
        "switched off for rendering (run the importer again after adding, removing or moving lamps)")
    return made
