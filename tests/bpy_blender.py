# Blender's command line for bpy, Blender as a Python module (the venvs of scripts/setup-venv.sh):
#   PYTHON tests/bpy_blender.py [-b] [--factory-startup] [-noaudio] [--python-exit-code N] [FILE.blend]
#       [--python SCRIPT | --python-expr EXPR]... [-o PATH] [-F FORMAT] [-f FRAME] [-- ARGS...]
# does what `blender` does with those options: open FILE.blend (else the factory start-up file),
# run each script as __main__ with sys.argv ending in "-- ARGS" and render frame FRAME to PATH.
# A Python error exits with the --python-exit-code status (like blender, 0 without it); sys.exit(n)
# exits n.  The Blender tests run on each bpy through tests/bpy-blender, which calls this.
import os
import runpy
import sys
import traceback


def main(argv):
    rest = argv[argv.index("--"):] if "--" in argv else []
    opts = argv[:len(argv) - len(rest)]
    blend, actions, err_code, out, fmt, frame = None, [], 0, None, None, None
    i = 0
    while i < len(opts):
        a = opts[i]
        if a in ("-b", "--background", "--factory-startup", "-noaudio"):
            pass
        elif a == "--python-exit-code":
            i += 1
            err_code = int(opts[i])
        elif a in ("--python", "-P", "--python-expr"):
            i += 1
            actions.append((a, opts[i]))
        elif a in ("-o", "--render-output"):
            i += 1
            out = opts[i]
        elif a in ("-F", "--render-format"):
            i += 1
            fmt = opts[i]
        elif a in ("-f", "--render-frame"):
            i += 1
            actions.append(("-f", opts[i]))
        elif a.endswith(".blend") and blend is None:
            blend = a
        else:
            print(f"bpy_blender.py: option {a} is not supported", file=sys.stderr)
            return 2
        i += 1
    import bpy
    sys.argv = ["blender"] + argv          # scripts look for "--" in sys.argv as under blender
    if blend:
        bpy.ops.wm.open_mainfile(filepath=os.path.abspath(blend))
    else:
        bpy.ops.wm.read_factory_settings(use_empty=False)
    for kind, arg in actions:
        try:
            if kind == "--python-expr":
                exec(compile(arg, "<string>", "exec"), {"__name__": "__main__"})
            elif kind == "-f":
                sc = bpy.context.scene
                if out:
                    sc.render.filepath = out
                if fmt:
                    sc.render.image_settings.file_format = fmt
                sc.frame_set(int(arg))
                bpy.ops.render.render(write_still=True)
            else:
                runpy.run_path(os.path.abspath(arg), run_name="__main__")
        except SystemExit as e:
            return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
        except Exception:
            traceback.print_exc()
            if err_code:
                return err_code
    return 0


if __name__ == "__main__":
    rc = main(sys.argv[1:])
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(rc)          # bpy's atexit clean-up can take seconds and print noise
