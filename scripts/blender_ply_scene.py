# blender_ply_scene.py: a Blender file holding the placed meshes of a `skinbake export mitsuba`
# directory, so that the Blender importer (--scene-json) renders the same scene as POV-Ray and
# Mitsuba (scripts/validate-mitsuba.sh).
#
#   blender -b --factory-startup --python scripts/blender_ply_scene.py -- MTS_DIR OUT.blend
#
# Each OBJECT.ply of MTS_DIR (binary little-endian float x y z nx ny nz [u v], faces of 3: written
# by meshply.c in Mitsuba's frame, scene units) becomes a smooth-shaded mesh object OBJECT with the
# file's normals.  Mitsuba's frame is the scene's with z mirrored, (x, y, -z); the importer maps a
# scene point (x, y, z) to Blender's (x, z, y) * unit_mm / 1000 (skinbake_import/scenejson.py),
# so a PLY point (a, b, c) goes to (a, -c, b) * unit_mm / 1000: a rotation, faces keep their
# winding.  Plain Python (struct), so Debian's Blender without numpy runs it too.
import json
import os
import struct
import sys

import bpy


def read_ply(path):
    with open(path, "rb") as f:
        nv = nf = 0
        props = []
        while True:
            w = f.readline().decode("ascii").split()
            if w == ["end_header"]:
                break
            if w[:2] == ["element", "vertex"]:
                nv = int(w[2])
            elif w[:2] == ["element", "face"]:
                nf = int(w[2])
            elif w[:2] == ["property", "float"]:
                props.append(w[2])
        k = len(props)
        flat = struct.unpack("<%df" % (k * nv), f.read(4 * k * nv))
        verts = [flat[i * k:i * k + 6] for i in range(nv)]
        faces = []
        for _ in range(nf):
            n, a, b, c = struct.unpack("<B3i", f.read(13))
            if n != 3:
                raise SystemExit("blender_ply_scene.py: %s: a face of %d vertices (3 expected)" % (path, n))
            faces.append((a, b, c))
    return verts, faces


def main(argv):
    mts, out = argv
    with open(os.path.join(mts, "scene.json")) as f:
        scale = json.load(f)["unit_mm"] / 1000.0
    bpy.ops.wm.read_factory_settings(use_empty=True)
    names = sorted(n[:-4] for n in os.listdir(mts) if n.endswith(".ply"))
    if not names:
        raise SystemExit("blender_ply_scene.py: no .ply in " + mts)
    for name in names:
        verts, faces = read_ply(os.path.join(mts, name + ".ply"))
        me = bpy.data.meshes.new(name)
        me.from_pydata([(v[0] * scale, -v[2] * scale, v[1] * scale) for v in verts], [], faces)
        me.polygons.foreach_set("use_smooth", [True] * len(faces))
        if hasattr(me, "use_auto_smooth"):          # 3.x: custom normals need it
            me.use_auto_smooth = True
        me.normals_split_custom_set_from_vertices([(v[3], -v[5], v[4]) for v in verts])
        me.validate()
        ob = bpy.data.objects.new(name, me)
        bpy.context.scene.collection.objects.link(ob)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(out))
    print("blender_ply_scene.py: %s: %s" % (out, ", ".join(names)))


main(sys.argv[sys.argv.index("--") + 1:])
