"""The meshes that get the material: finding them, their UVs and UV size, assigning."""
import math

import bpy

from .common import PREFIX, UV_SIZE_PROP, SkinbakeError, say


def find_objects(names):
    """The mesh objects called NAMES, or SkinbakeError naming the missing ones."""
    obs, missing = [], []
    for n in names:
        ob = bpy.data.objects.get(n)
        if ob is None:
            missing.append(n)
        elif ob.type != "MESH":
            raise SkinbakeError(f"--objects: '{n}' is a {ob.type.lower()} object, not a mesh")
        else:
            obs.append(ob)
    if missing:
        have = sorted(o.name for o in bpy.data.objects if o.type == "MESH")
        shown = ", ".join(have[:20]) + (" ..." if len(have) > 20 else "")
        raise SkinbakeError(f"--objects: no object named {', '.join(repr(x) for x in missing)} "
                            f"(mesh objects in the file: {shown or 'none'})")
    return obs


def generate_uvs(ob):
    """Smart UV Project on OB (object mode afterwards)."""
    vl = bpy.context.view_layer
    prev = vl.objects.active
    if bpy.context.object is not None and bpy.context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    vl.objects.active = ob
    for o in vl.objects:
        o.select_set(o == ob)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.uv.smart_project(island_margin=0.002)
    bpy.ops.object.mode_set(mode="OBJECT")
    vl.objects.active = prev


def measure_uv_size(ob, unit_scale=1.0):
    """(metres per UV unit, 10th and 90th percentile over the surface) of OB's render UV map:
    sqrt(world surface area / UV area) over all faces, and per face weighted by area; None when
    the UV area is zero."""
    me = ob.data
    uvl = next((u for u in me.uv_layers if u.active_render), me.uv_layers.active)
    if uvl is None:
        return None
    mw = ob.matrix_world
    co = [mw @ v.co for v in me.vertices]
    uv = uvl.data
    a3 = a2 = 0.0
    faces = []
    for p in me.polygons:
        idx = list(p.loop_indices)
        v0 = co[me.loops[idx[0]].vertex_index]
        u0 = uv[idx[0]].uv
        f3 = f2 = 0.0
        for k in range(1, len(idx) - 1):          # fan triangles
            v1, v2 = co[me.loops[idx[k]].vertex_index], co[me.loops[idx[k + 1]].vertex_index]
            f3 += (v1 - v0).cross(v2 - v0).length / 2
            u1, u2 = uv[idx[k]].uv, uv[idx[k + 1]].uv
            f2 += abs((u1.x - u0.x) * (u2.y - u0.y) - (u2.x - u0.x) * (u1.y - u0.y)) / 2
        a3 += f3
        a2 += f2
        if f2 > 0 and f3 > 0:
            faces.append((math.sqrt(f3 / f2), f3))
    if a2 <= 0 or not faces:
        return None
    faces.sort()
    total, acc, q = sum(f[1] for f in faces), 0.0, {}
    for d, w in faces:
        acc += w
        for p in (0.1, 0.9):
            if p not in q and acc >= p * total:
                q[p] = d
    k = unit_scale
    return math.sqrt(a3 / a2) * k, q[0.1] * k, q[0.9] * k


def prepare_objects(obs, m, mode, no_detail, uv_size=None, gen_uvs=False, unit_scale=1.0):
    """Check UVs where the detail map needs them (or generate them) and store each object's UV
    size [m per UV unit] in its skinbake_uv_size property."""
    detail = not (no_detail or m["detail"].get("flat") or not m["detail"].get("tile_mm"))
    for ob in obs:
        if detail and not ob.data.uv_layers:
            if not gen_uvs:
                raise SkinbakeError(f"object '{ob.name}' has no UV map: the detail normal map needs one "
                                    "(add UVs, or pass --generate-uvs for a Smart UV Project, or --no-detail)")
            generate_uvs(ob)
            say(f"'{ob.name}' had no UV map: generated one with Smart UV Project (the detail map has seams "
                "at the island borders)")
        if not detail:
            continue
        if uv_size is not None:
            ob[UV_SIZE_PROP] = float(uv_size)
            say(f"'{ob.name}': UV size {uv_size:.4g} m per UV unit (--uv-size)")
            continue
        r = measure_uv_size(ob, unit_scale)
        if r is None:
            raise SkinbakeError(f"object '{ob.name}': its UV map has zero area; fix the UVs or give --uv-size")
        s, lo, hi = r
        ob[UV_SIZE_PROP] = s
        say(f"'{ob.name}': UV size {s:.4g} m per UV unit (measured: sqrt(surface area / UV area)); "
            f"detail tile {float(m['detail']['tile_mm']):g} mm")
        if hi > 1.25 * lo:
            say(f"note: the UV density of '{ob.name}' varies: {lo:.3g} to {hi:.3g} m per UV unit over 80% of "
                "its surface, so the detail maps are at their true size only where it is "
                f"{s:.3g}; give --uv-size for the part that matters (e.g. the face)")


def assign(obs, mat):
    """MAT into every material slot of each object (one slot if it has none).  The materials it
    replaces get a fake user, so that saving the file keeps them."""
    for ob in obs:
        if not ob.material_slots:
            ob.data.materials.append(mat)
        for s in ob.material_slots:
            old = s.material
            if old is not None and old != mat and not old.name.startswith(PREFIX):
                if not old.use_fake_user:
                    old.use_fake_user = True
                    say(f"material '{old.name}' of '{ob.name}' kept in the file (fake user)")
            s.material = mat
