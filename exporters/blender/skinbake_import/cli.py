"""The command line: `blender -b [FILE.blend] --python import_skin.py -- SET [options]`
(import_skin.py, beside this package, calls run)."""
import os
import sys

import bpy

from .common import SkinbakeError, say
from .imageset import read_manifest
from .importer import import_set
from .objects import find_objects
from .scene import build_scene, engine_id, render
from .scenejson import apply_scene_json, read_scene_json
from .schema import VERSION


def main(argv):
    import argparse

    class Parser(argparse.ArgumentParser):
        def error(self, message):
            raise SkinbakeError(message)

    ap = Parser(prog="import_skin.py", description=f"Import a skinbake image set (importer {VERSION}).")
    ap.add_argument("dir", help="image-set directory (holds manifest.json), or its manifest.json")
    ap.add_argument("--mode", choices=("general", "exact"), default="general",
                    help="material mode (default general)")
    ap.add_argument("--objects", metavar="A,B", help="mesh objects that get the material (default: the demo object)")
    ap.add_argument("--scene", choices=("sphere", "plane", "box", "none"), default=None,
                    help="demo scene to build (default sphere with --render or --save and no .blend "
                         "file or --objects, else none)")
    ap.add_argument("--render", metavar="FILE", help="render to FILE (.exr: linear float for measuring; else 8-bit sRGB PNG)")
    ap.add_argument("--save", metavar="FILE", help="save the result as a .blend (image paths relative)")
    ap.add_argument("--pack", action="store_true", help="pack the images into the .blend")
    ap.add_argument("--engine", choices=("CYCLES", "BLENDER_EEVEE"), default=None,
                    help="render engine (default: the file's; Cycles for the demo scene)")
    ap.add_argument("--scene-json", metavar="FILE",
                    help="add the camera and lights of FILE (scene.json of `skinbake scene`, or a directory "
                         "holding one), as the POV-Ray export of that scene has them (default: none)")
    ap.add_argument("--res", type=int, default=None,
                    help="render size [px] (demo default 64; with --scene-json the width, its aspect kept)")
    ap.add_argument("--samples", type=int, default=None, help="samples (demo default 16)")
    ap.add_argument("--world", type=float, default=0.0, help="demo world radiance (default 0)")
    ap.add_argument("--sun-strength", type=float, default=None,
                    help="demo sun irradiance [W/m^2], 0 = no sun (default: the manifest's)")
    ap.add_argument("--view", nargs=2, type=float, metavar=("ELEV", "AZIM"), default=None,
                    help="demo camera elevation and azimuth [deg] (default: the manifest's reference view)")
    ap.add_argument("--uv-size", type=float, default=None,
                    help="metres per UV unit for tiling the detail maps (default: measured per object)")
    ap.add_argument("--generate-uvs", action="store_true", help="give objects without UVs a Smart UV Project")
    ap.add_argument("--no-detail", action="store_true", help="leave out the normal map")
    ap.add_argument("--no-specular", action="store_true", help="general mode without the specular layer")
    ap.add_argument("--no-calibration", action="store_true",
                    help="general mode: Base Color = albedo, without the Cycles 3.x correction")
    a = ap.parse_args(argv)
    if a.uv_size is not None and not (a.uv_size > 0):
        raise SkinbakeError(f"--uv-size = {a.uv_size} must be > 0 metres per UV unit")
    for k in ("res", "samples"):
        v = getattr(a, k)
        if v is not None and not 1 <= v <= 16384:
            raise SkinbakeError(f"--{k} = {v} is out of range [1, 16384]")
    d = a.dir[:-len("manifest.json")] if a.dir.endswith("manifest.json") else a.dir
    m = read_manifest(d or ".")
    say(f"{VERSION} in Blender {bpy.app.version_string.split()[0]}: {m['_dir']} (format {m['format_version']}, "
        f"{'flat' if m['detail']['flat'] else 'textured'} detail)")
    have_file = bool(bpy.data.filepath)
    if a.scene_json and a.scene not in (None, "none"):
        raise SkinbakeError(f"--scene {a.scene} has its own camera and sun; --scene-json lights and frames "
                            "the file's objects (give a .blend or --scene none)")
    sj = read_scene_json(a.scene_json) if a.scene_json else None
    demo = (a.render or a.save) and not have_file and not a.objects and not sj
    kind = a.scene or ("sphere" if demo else "none")
    if kind != "none" and have_file:
        raise SkinbakeError(f"--scene {kind} builds a new scene and would discard {bpy.data.filepath}; "
                            "use --objects to put the material on the file's own meshes")
    obs = []
    if a.objects:
        obs = find_objects([x.strip() for x in a.objects.split(",") if x.strip()])
    scene = bpy.context.scene
    if kind != "none":
        strength = m["exact"].get("sun_strength_w_m2", 3.0) if a.sun_strength is None else a.sun_strength
        scene, obj = build_scene(m, kind, a.res or 64, a.samples or 16, a.world, strength, a.view,
                                 a.engine or "CYCLES")
        obs = obs or [obj]
    else:
        if a.engine:
            scene.render.engine = engine_id(a.engine)
        if sj:
            apply_scene_json(sj, scene, a.res)
        elif a.res:
            scene.render.resolution_x = scene.render.resolution_y = a.res
            scene.render.resolution_percentage = 100
        if a.samples:
            scene.cycles.samples = scene.eevee.taa_render_samples = a.samples
    import_set(m, scene, obs, a.mode, a.no_detail, a.no_specular, not a.no_calibration, a.uv_size,
               a.generate_uvs, engine_id(a.engine) if a.engine else scene.render.engine)
    if a.save:
        path = os.path.abspath(a.save)
        bpy.ops.wm.save_as_mainfile(filepath=path)
        if a.pack:
            bpy.ops.file.pack_all()
        else:
            bpy.ops.file.make_paths_relative()
        bpy.ops.wm.save_as_mainfile(filepath=path)
        say(f"saved {path}")
    if a.render:
        if scene.camera is None:
            raise SkinbakeError("--render: the scene has no camera")
        mean = render(scene, os.path.abspath(a.render))
        print("SKINBAKE_CENTER " + " ".join(f"{x:.6f}" for x in mean))


def run(argv):
    """main on the arguments after "--"; bad input prints "import_skin.py: error: ..." and exits 2."""
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    try:
        main(args)
    except SkinbakeError as e:
        print(f"import_skin.py: error: {e}", file=sys.stderr)
        sys.stdout.flush()
        sys.stderr.flush()
        sys.exit(2)
