#!/usr/bin/env python3
"""Measure each renderer's subsurface response over a grid of colours (scripts/sss_profile.py, real
renders) and write the calibration table the exporters fit with (`make calibrate`).

  scripts/calibrate-translucency.py [--renderer pov|cycles|all] [--out-dir tests/data/sss_calib]
                                    [--c-file src/export/sss_table.c] [--from-json]
  scripts/calibrate-translucency.py --bpy-python .venv-bpy45/bin/python [--samples 256]
                                    [--blender-c-file src/export/blender/blender_sss_table.c]

Per renderer it renders the slab at unit length scale (POV-Ray translucency 1 mm, Cycles radius
1 mm) for every colour of COLOURS (grey: the same colour in R, G and B, each channel kept) and
keeps G(r) at EDGES (the power leaving beyond r) per channel.  Both models
scale every length with their length parameter (POV-Ray: sigma_s' = 1/translucency; Cycles:
sigma_t ~ 1/radius), so one scale serves all radii.  The raw measurements go to
OUT_DIR/RENDERER.json with the renderer's version; the C table (the renderer, its version, the
colours, the edges and G) to C_FILE.  --from-json rewrites C_FILE from the stored JSON only.

--bpy-python PY measures the Cycles of a bpy venv (Blender as a Python module, through
tests/bpy-blender) instead: falloff "Random Walk (Skin)" on 4.x and later (what 3.x called
"Random Walk": the radius adjusted to the colour; 4.x's "Random Walk" takes the radius as given),
into OUT_DIR/cycles-MAJOR.MINOR.json.  Every cycles-*.json there goes into BLENDER_C_FILE, the
Blender exporter's tables per version (export/blender/blender_sss.h); Debian's Blender (3.4.1,
cycles.json) stays in C_FILE, which the POV-Ray exporter shares.
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
COLOURS = [0.01, 0.02, 0.04, 0.06, 0.09, 0.13, 0.18, 0.25, 0.33, 0.42, 0.52, 0.62, 0.72, 0.82, 0.92]
FAR = [0.0, 20.0, 40.0, 60.0, 75.0, 85.0]        # scripts/sss_profile.py's FAR_ANGLES
EDGES = [0.0] + [round(0.005 * 1.5 ** k, 6) for k in range(22)]          # 0 .. 37.4 mm
RENDERERS = {
    "pov": {"args": ["pov", "--samples", "800"], "far_samples": "200", "edges": EDGES, "id": "sss_pov"},
    # Cycles' walk enters and leaves through a cosine-weighted (Lambertian) direction, so its far
    # field is G(0) / pi at every angle; the C table takes it from G(0) (64 samples on a 32 px
    # fisheye), not from the far renders (32 samples on 8 x 8 px, one seed for every angle, so the
    # whole far table carried one noise draw: 1.4 % low at colour 0.18, which put +2.3 % red on a
    # flat translucent box in Blender).
    "cycles": {"args": ["cycles", "--method", "random_walk", "--samples", "64"], "far_samples": "32",
               "edges": [e for e in EDGES if e <= 20.0], "id": "sss_cycles", "far_from_g0": True},
}


def bpy_cycles_spec(samples):
    """The Cycles spec for a bpy venv: falloff by major version (set after the version is known)."""
    return {"args": ["cycles", "--samples", str(samples)], "edges": RENDERERS["cycles"]["edges"],
            "id": "sss_cycles", "far_from_g0": True}


def measure(name, out, part, spec=None):
    """Rings (G at the edges) or the far field (pi f at the far angles, fewer samples: no
    small rings to resolve) for every colour, grey (the same in R, G and B), into OUT, per
    channel: a renderer's channels differ by a few per cent at the same colour (POV-Ray draws
    its single-scattering samples per channel: colour 0.0395 gives G(0) = 0.0483, 0.0483,
    0.0472 in R, G, B), so each channel is fitted with its own table."""
    spec = spec or RENDERERS[name]
    out["colours"] = COLOURS
    key = "g" if part == "rings" else "far_pi_f"
    out[key] = [[None] * len(COLOURS) for _ in range(3)]
    for k, c in enumerate(COLOURS):
        extra = ["--edges", ",".join(map(str, spec["edges"]))] if part == "rings" else \
            ["--edges", "0,1", "--far", "--samples", spec["far_samples"]] + spec.get("far_args", [])
        cmd = [sys.executable, os.path.join(HERE, "sss_profile.py")] + spec["args"] + [
            "--colour", f"{c},{c},{c}", "--radius", "1"] + extra
        print(f"calibrate: {name} {part} colour {c}", file=sys.stderr)
        r = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
        for ch in range(3):
            rows = len(FAR) if spec.get("far_rows") else 1     # one theta_i row kept for every row
            out[key][ch][k] = [row[ch] for row in r[key]] * rows
        out["renderer"], out["version"], out["closure"] = r["renderer"], r["version"], r["closure"]
        if part == "rings":
            out["edges_mm"] = spec["edges"]
            out["params"] = {key: v for key, v in r["params"].items() if key != "colour"}
        else:
            out["far_angles_deg"] = r["far_angles_deg"]
    return out


def wrapped(head, items, tail, wrap):
    """HEAD, the comma-separated ITEMS, TAIL: one line, or (WRAP) lines of at most 100 columns."""
    if not wrap:
        return [head + ", ".join(items) + tail]
    lines, cur = [], head
    for k, x in enumerate(items):
        piece = x + (", " if k + 1 < len(items) else "")
        if len((cur + piece).rstrip().expandtabs(8)) > 100:
            lines.append(cur.rstrip())
            cur = "\t"
        cur += piece
    if len((cur + tail).expandtabs(8)) > 100:
        lines.append(cur.rstrip())
        cur = ""
    return lines + [cur + tail]


def table_lines(pre, t, far_from_g0, storage="", wrap=False):
    """C arrays and the struct sss_table PRE_table of one measurement T (its JSON).  FAR_FROM_G0:
    the far field is G(0) at every angle (Cycles' walk is Lambertian both ways).  WRAP: lines of
    at most 100 columns."""
    nc, ne = len(t["colours"]), len(t["edges_mm"])
    far_deg = t.get("far_angles_deg") or [0.0, 85.0]
    nf = len(far_deg)
    lines = wrapped(f"static const double {pre}_colour[{nc}] = {{ ",
                    [f"{c:.6g}" for c in t["colours"]], " };", wrap)
    lines += wrapped(f"static const double {pre}_edge[{ne}] = {{ ",
                     [f"{e:.6g}" for e in t["edges_mm"]], " };", wrap)
    lines.append(f"static const double {pre}_g[{3 * nc * ne}] = {{")
    for ch in range(3):
        for row in t["g"][ch]:
            lines += wrapped("\t", [f"{max(v, 0.0):.6e}" for v in row], ",", wrap)
    lines.append("};")
    lines += wrapped(f"static const double {pre}_far_deg[{nf}] = {{ ",
                     [f"{a:.6g}" for a in far_deg], " };", wrap)
    lines.append(f"static const double {pre}_far[{3 * nc * nf * nf}] = {{")
    for ch in range(3):
        for k in range(nc):
            row = [t["g"][ch][k][0]] * (nf * nf) if far_from_g0 else t["far_pi_f"][ch][k]
            lines += wrapped("\t", [f"{max(v, 0.0):.5e}" for v in row], ",", wrap)
    lines.append("};")
    lines += wrapped(f"{storage}const struct sss_table {pre}_table = {{ ",
                     [f"\"{t['renderer']}\"", f"\"{t['version']}\"", f"\"{t['closure']}\"",
                      f"{t['params']['ior']}", f"{nc}", f"{ne}", f"{nf}", f"{pre}_colour",
                      f"{pre}_edge", f"{pre}_g", f"{pre}_far_deg", f"{pre}_far"], " };", wrap)
    lines.append("")
    return lines


def c_table(tables):
    lines = ["/* sss_table.c: GENERATED by scripts/calibrate-translucency.py (`make calibrate`) from",
             " * tests/data/sss_calib/RENDERER.json, real renders of a flat slab; do not edit by hand.",
             " * G[colour][edge]: fraction of the incident power leaving beyond edge r [mm] at unit",
             " * length scale (see export/sss_fit.h). */",
             '#include "config.h"', '#include <stddef.h>', "", '#include "export/sss_fit.h"', ""]
    for name, spec in RENDERERS.items():
        t = tables.get(name)
        pre = spec["id"].lower()
        if t is None or "far_pi_f" not in t:       # not measured yet: an empty table, refused by the fit
            lines.append(f"const struct sss_table {pre}_table = {{ \"{name}\", \"not calibrated\", \"\", 1.4, "
                         "0, 0, 0, NULL, NULL, NULL, NULL, NULL };")
            lines.append("")
            continue
        lines += table_lines(pre, t, spec.get("far_from_g0"))
    return "\n".join(lines)


def blender_c_table(bpy_tables):
    """The Blender exporter's Cycles tables, one per version measured (cycles-*.json, oldest
    first), after Debian's (sss_cycles_table in sss_table.c)."""
    lines = ["/* blender_sss_table.c: GENERATED by scripts/calibrate-translucency.py",
             " * --bpy-python (`make calibrate-blender`) from tests/data/sss_calib/cycles-*.json,",
             " * real renders of a flat slab in each bpy venv; do not edit by hand.  The Cycles",
             " * calibrations per Blender version (export/blender/blender_sss.h; the table format",
             " * is export/sss_fit.h's).  Over 600 lines because it is generated data: the rows of",
             " * G and of the far field per channel and colour, wrapped at 100 columns. */",
             '#include "config.h"', '#include <stddef.h>', "",
             '#include "export/blender/blender_sss.h"', ""]
    names = ["&sss_cycles_table"]
    for t in bpy_tables:
        pre = "blender_sss_cycles_" + "_".join(t["version"].split()[0].split(".")[:2])
        lines += table_lines(pre, t, "far_pi_f" not in t, "static ", wrap=True)
        names.append(f"&{pre}_table")
    lines += wrapped("const struct sss_table *const blender_sss_tables[] = { ", names + ["NULL"],
                     " };", True)
    return "\n".join(lines) + "\n"


def bpy_version(py):
    out = subprocess.run([py, "-c", "import bpy; print('BPYVER', *bpy.app.version[:2])"],
                         check=True, capture_output=True, text=True).stdout
    return [int(x) for x in out.split("BPYVER")[1].split()[:2]]


def measure_bpy(py, samples, out_dir, part):
    """Rings of every colour in the bpy of PY (falloff by major version) to
    OUT_DIR/cycles-M.N.json."""
    major, minor = bpy_version(py)
    method = "random_walk_skin" if major >= 4 else "random_walk"
    # The far field of 4.x's skin walk is not Lambertian (its exit: pi f / G(0) = 0.92 at theta_o
    # = 0, 1.22 at 85 deg for colour 0.15) but does not depend on theta_i (within 0.5 % at colours
    # 0.15, 0.5, 0.9 in 4.5): one row at theta_i = 0, kept for every row.  32 x 32 px at 128
    # samples: 16 x 16 at 128 (one seed for every angle) put the whole row of colour 0.04-0.06
    # 1.3 % high, and the flat box's green 1.4 % low.
    spec = {"args": ["cycles", "--method", method, "--samples", str(samples)],
            "edges": RENDERERS["cycles"]["edges"], "id": "sss_cycles", "far_samples": "128",
            "far_args": ["--far-theta-i-0", "--far-size", "32"], "far_rows": True}
    os.environ["BLENDER"] = os.path.join(HERE, "..", "tests", "bpy-blender")
    os.environ["BPY_PYTHON"] = py
    path = os.path.join(out_dir, f"cycles-{major}.{minor}.json")
    t = {}
    if part == "far" and os.path.exists(path):
        with open(path) as f:
            t = json.load(f)
    for pt in ("rings", "far"):
        if part in ("all", pt):
            measure(f"cycles {major}.{minor}", t, pt, spec)
    with open(path + ".tmp", "w") as f:
        json.dump(t, f, indent=1)
    os.replace(path + ".tmp", path)


def version_key(t):
    return [int(x) for x in t["version"].split()[0].split(".")]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--renderer", default="all", choices=["all"] + list(RENDERERS))
    p.add_argument("--out-dir", default=os.path.join(HERE, "..", "tests", "data", "sss_calib"))
    p.add_argument("--c-file", default=os.path.join(HERE, "..", "src", "export", "sss_table.c"))
    p.add_argument("--blender-c-file", default=os.path.join(HERE, "..", "src", "export", "blender",
                                                            "blender_sss_table.c"))
    p.add_argument("--bpy-python", help="measure the Cycles of this bpy venv's python "
                   "(cycles-M.N.json)")
    p.add_argument("--samples", type=int, default=256,
                   help="Cycles samples per pixel for --bpy-python")
    p.add_argument("--from-json", action="store_true")
    p.add_argument("--part", default="all", choices=["all", "rings", "far"])
    a = p.parse_args()
    os.makedirs(a.out_dir, exist_ok=True)
    if a.bpy_python:
        if not a.from_json:
            measure_bpy(a.bpy_python, a.samples, a.out_dir, a.part)
        bpy_tables = []
        for fn in sorted(os.listdir(a.out_dir)):
            if fn.startswith("cycles-") and fn.endswith(".json"):
                with open(os.path.join(a.out_dir, fn)) as f:
                    bpy_tables.append(json.load(f))
        bpy_tables.sort(key=version_key)
        with open(a.blender_c_file + ".tmp", "w") as f:
            f.write(blender_c_table(bpy_tables))
        os.replace(a.blender_c_file + ".tmp", a.blender_c_file)
        print(f"calibrate: wrote {a.blender_c_file}", file=sys.stderr)
        return
    tables = {}
    for name in RENDERERS:
        path = os.path.join(a.out_dir, name + ".json")
        if not a.from_json and a.renderer in ("all", name):
            t = {}
            if a.part == "far" and os.path.exists(path):
                with open(path) as f:
                    t = json.load(f)
            for part in ("rings", "far"):
                if a.part in ("all", part):
                    measure(name, t, part)
            with open(path + ".tmp", "w") as f:
                json.dump(t, f, indent=1)
            os.replace(path + ".tmp", path)
        if os.path.exists(path):
            with open(path) as f:
                tables[name] = json.load(f)
    with open(a.c_file + ".tmp", "w") as f:
        f.write(c_table(tables))
    os.replace(a.c_file + ".tmp", a.c_file)
    print(f"calibrate: wrote {a.c_file}", file=sys.stderr)


if __name__ == "__main__":
    main()
