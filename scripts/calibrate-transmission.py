#!/usr/bin/env python3
"""Measure the transmittance of Cycles' random walk through a slab, per colour and thickness at
unit radius (docs/translucency.md, Back light), in the real renderer, and write the table the
Blender exporter's thickness weight uses (export/blender/blender_sss_thick.h).

  scripts/calibrate-transmission.py [--blender blender] [--samples 128] [--json OUT.json]
  scripts/calibrate-transmission.py --from-json tests/data/sss_calib/cycles-trans-*.json \
                                    --c-file src/export/blender/blender_sss_trans.c
  scripts/calibrate-transmission.py --albedo [--samples 1024] --json OUT.json
  scripts/calibrate-transmission.py --from-json tests/data/sss_calib/cycles-albedo-*.json \
                                    --c-file src/export/blender/blender_sss_albedo.c

The slab of scripts/sss_profile.py --back (60 mm wide, lit from below by a sun of irradiance 1,
a 180-degree fisheye 1e-3 mm above the top face's centre, cosine-weighted mean = the exitance over
all exit directions), the Subsurface Scattering node with the falloff the translucent mode uses
(3.x "Random Walk", 4.x+ "Random Walk (Skin)"), radius 1 mm, IOR 1.4, for each thickness X of
THICK [mm] and each colour of COLOURS.  The walk scales every length with the radius, so the
transmittance of a slab d thick at radius L is T(d / L) of this table.  The channels are
independent in the walk (the same colour gives the same G in every channel, docs), so each
render measures three colours, one per channel.  One Blender session renders them all.

--albedo measures the walk's albedo G(0) instead (the slab 30 mm thick lit from above, the
profile's fisheye without a disc) on a dense grid of colours (ALBEDO_COLOURS) at many samples:
the translucent remainder takes the node's far field off the table, and the profile calibration's
G(0) (linear in the colour between 15 nodes; 3.4.1 at 64 samples, which reads 0.6 % low) put the
flat box 1-2 % off where the fitted colour falls between nodes (3.4.1 blue 0.029: the table
interpolates 0.03007, the walk returns 0.03054 at 1024 and 4096 samples;
export/blender/blender_sss_albedo.h).
"""
import argparse
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
COLOURS = [0.01, 0.02, 0.04, 0.06, 0.09, 0.13, 0.18, 0.25, 0.33, 0.42, 0.52, 0.62, 0.72, 0.82, 0.92]
THICK = [0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.5, 7.0, 10.0, 15.0]
# Dense where G(0) / colour bends (1.10 at 0.01, 1.07 at 0.02, 1.02 at 0.04, 1.00 from 0.06).
ALBEDO_COLOURS = [0.01, 0.0125, 0.015, 0.0175, 0.02, 0.0225, 0.025, 0.0275, 0.03, 0.0325, 0.035, 0.04,
                  0.045, 0.05, 0.055, 0.06, 0.07, 0.08, 0.09, 0.1, 0.115, 0.13, 0.15, 0.18, 0.21, 0.25,
                  0.29, 0.33, 0.42, 0.52, 0.62, 0.72, 0.82, 0.92]


def inner(a):
    """Inside Blender: T per colour (rows) and thickness (columns)."""
    import bpy
    sys.path.insert(0, HERE)
    import sss_profile as sp
    skin = bpy.app.version[0] >= 4
    method = "random_walk_skin" if skin else "random_walk"
    colours, thick = (ALBEDO_COLOURS, [30.0]) if a.albedo else (COLOURS, THICK)
    t = [[0.0] * len(thick) for _ in colours]
    for j, x in enumerate(thick):
        pa = sp.parse(["cycles", "--colour", "0.5,0.5,0.5", "--radius", "1", "--method", method]
                      + ([] if a.albedo else ["--back"])
                      + ["--depth", str(x), "--edges", "0", "--samples", str(a.samples), "--size", str(a.size)])
        sc, occ = sp._cycles_scene(pa)
        occ.hide_render = True
        node = next(n for n in bpy.data.materials["sss"].node_tree.nodes
                    if n.bl_idname == "ShaderNodeSubsurfaceScattering")
        for k in range(0, len(colours), 3):
            cols = (colours + colours[-1:] * 2)[k:k + 3]
            node.inputs["Color"].default_value = (*cols, 1.0)
            path = os.path.join(bpy.app.tempdir, "trans.exr")
            sc.render.filepath = path
            bpy.ops.render.render(write_still=True)
            img = bpy.data.images.load(path, check_existing=False)
            img.colorspace_settings.name = "Non-Color"
            n = img.size[0]
            flat = list(img.pixels)
            bpy.data.images.remove(img)
            g = sp.weighted_mean([flat[4 * i:4 * i + 3] for i in range(n * n)], n, math.pi)
            for c in range(3):
                if k + c < len(colours):
                    t[k + c][j] = g[c]
            print("TRANS x=%g colours %s: %s" % (x, cols, g), flush=True)
    if a.albedo:
        return {"renderer": "cycles", "version": bpy.app.version_string, "falloff": method,
                "radius_mm": 1.0, "ior": 1.4, "samples": a.samples, "size": a.size, "depth_mm": thick[0],
                "colours": colours, "g0": [row[0] for row in t]}
    return {"renderer": "cycles", "version": bpy.app.version_string, "falloff": method,
            "radius_mm": 1.0, "ior": 1.4, "samples": a.samples, "size": a.size,
            "colours": COLOURS, "thickness_mm": THICK, "t": t}


C_HEAD = """/* blender_sss_trans.c: GENERATED by scripts/calibrate-transmission.py --from-json
 * from tests/data/sss_calib/cycles-trans-*.json (real renders); do not edit by hand.
 * The transmittance of Cycles' random walk through a slab lit from behind, per Blender
 * version, colour and thickness at radius 1 mm (export/blender/blender_sss_thick.h). */
#include "config.h"
#include <stddef.h>

#include "export/blender/blender_sss_thick.h"
"""


C_HEAD_ALBEDO = """/* blender_sss_albedo.c: GENERATED by scripts/calibrate-transmission.py --from-json
 * from tests/data/sss_calib/cycles-albedo-*.json (real renders); do not edit by hand.
 * The albedo G(0) of Cycles' random walk on a thick slab lit from above, per Blender version
 * and colour (export/blender/blender_sss_albedo.h). */
#include "config.h"
#include <stddef.h>

#include "export/blender/blender_sss_albedo.h"
"""


def c_file_albedo(runs, out):
    s = [C_HEAD_ALBEDO]
    names = []
    for r in runs:
        ser = "_".join(r["version"].split(".")[:2])
        n = len(r["colours"])
        s.append("\nstatic const double albedo_%s_colour[%d] = {\n%s };\n" % (ser, n, ",\n".join(
            "\t" + ", ".join("%g" % c for c in r["colours"][i:i + 10]) for i in range(0, n, 10))))
        s.append("static const double albedo_%s_g0[%d] = {\n%s };\n" % (ser, n, ",\n".join(
            "\t" + ", ".join("%.6e" % g for g in r["g0"][i:i + 6]) for i in range(0, n, 6))))
        s.append("static const struct sss_albedo_table albedo_%s = { \"%s\", %d, %d, albedo_%s_colour,\n"
                 "\talbedo_%s_g0 };\n" % (ser, r["version"], r["samples"], n, ser, ser))
        names.append("&albedo_%s" % ser)
    s.append("\nconst struct sss_albedo_table *const blender_sss_albedo_tables[] = {\n\t%s, NULL };\n"
             % ", ".join(names))
    with open(out, "w") as f:
        f.write("".join(s))


def c_file(paths, out):
    runs = sorted((json.load(open(p)) for p in paths), key=lambda r: [int(x) for x in r["version"].split(".")[:2]])
    if all("g0" in r for r in runs):
        c_file_albedo(runs, out)
        return
    s = [C_HEAD]
    names = []
    for r in runs:
        ser = "_".join(r["version"].split(".")[:2])
        nc, nx = len(r["colours"]), len(r["thickness_mm"])
        s.append("\nstatic const double trans_%s_colour[%d] = {\n\t%s };\n" % (ser, nc, ", ".join("%g" % c for c in r["colours"])))
        s.append("static const double trans_%s_x[%d] = { %s };\n" % (ser, nx, ", ".join("%g" % x for x in r["thickness_mm"])))
        vals = ["%.6e" % max(v, 0.0) for row in r["t"] for v in row]
        rows = ",\n".join("\t" + ", ".join(vals[i:i + 6]) for i in range(0, len(vals), 6))
        s.append("static const double trans_%s_t[%d] = {\n%s };\n" % (ser, nc * nx, rows))
        s.append("static const struct sss_trans_table trans_%s = { \"%s\", \"%s\", %d, %d,\n"
                 "\ttrans_%s_colour, trans_%s_x, trans_%s_t };\n" % (ser, r["version"], r["falloff"], nc, nx, ser, ser, ser))
        names.append("&trans_%s" % ser)
    s.append("\nconst struct sss_trans_table *const blender_sss_trans_tables[] = {\n\t%s, NULL };\n" % ", ".join(names))
    with open(out, "w") as f:
        f.write("".join(s))


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--blender", default=os.environ.get("BLENDER", "blender"))
    p.add_argument("--samples", type=int, default=128)
    p.add_argument("--size", type=int, default=32)
    p.add_argument("--json")
    p.add_argument("--albedo", action="store_true", help="the walk's albedo G(0) per colour instead")
    p.add_argument("--from-json", nargs="+")
    p.add_argument("--c-file")
    p.add_argument("--inner", action="store_true", help=argparse.SUPPRESS)
    a = p.parse_args(argv)
    if a.from_json:
        c_file(a.from_json, a.c_file)
        return
    if a.inner:
        print("TRANS_RESULT " + json.dumps(inner(a)))
        return
    res = subprocess.run([a.blender, "-b", "--factory-startup", "-noaudio", "--python-exit-code", "1",
                          "--python", os.path.abspath(__file__), "--", "--inner", "--samples", str(a.samples),
                          "--size", str(a.size)] + (["--albedo"] if a.albedo else []), capture_output=True, text=True)
    line = [ln for ln in res.stdout.splitlines() if ln.startswith("TRANS_RESULT ")]
    if res.returncode != 0 or not line:
        sys.exit("calibrate-transmission: blender failed:\n" + res.stdout[-1500:] + res.stderr[-1500:])
    r = json.loads(line[0][13:])
    text = json.dumps(r, indent=1) + "\n"
    if a.json:
        with open(a.json, "w") as f:
            f.write(text)
    else:
        print(text)


if __name__ == "__main__":
    main()
