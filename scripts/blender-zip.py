#!/usr/bin/env python3
"""Build the importer's Blender packages from the one source, exporters/blender/skinbake_import/:

  blender-zip.py extension SRC_DIR OUT.zip   Blender 4.2+ extension: the package's files at the zip's
                                             root, blender_manifest.toml among them
  blender-zip.py addon SRC_DIR OUT.zip       legacy add-on (Blender 3.x, 4.x): the folder
                                             skinbake_import/ with __init__.py (bl_info)

The versions in blender_manifest.toml, bl_info and schema.VERSION must agree.  The zips are
byte-reproducible (sorted names, fixed dates).  Exit 2 with a message on a mismatch."""
import ast
import os
import re
import sys
import zipfile

FILES_EXT = (".py", ".toml")
DATE = (2024, 1, 1, 0, 0, 0)


def versions(src):
    toml = open(os.path.join(src, "blender_manifest.toml"), encoding="utf-8").read()
    man = re.search(r'^version\s*=\s*"([^"]+)"', toml, re.M).group(1)
    init = ast.parse(open(os.path.join(src, "__init__.py"), encoding="utf-8").read())
    bl = next(ast.literal_eval(n.value) for n in init.body
              if isinstance(n, ast.Assign) and getattr(n.targets[0], "id", "") == "bl_info")
    schema = open(os.path.join(src, "schema.py"), encoding="utf-8").read()
    ver = re.search(r'^VERSION\s*=\s*"([^"]+)"', schema, re.M).group(1)
    return {"blender_manifest.toml version": man, "bl_info version": ".".join(map(str, bl["version"])),
            "schema.VERSION": ver}


def main(argv):
    if len(argv) != 4 or argv[1] not in ("extension", "addon"):
        print(__doc__, file=sys.stderr)
        return 2
    kind, src, out = argv[1:]
    v = versions(src)
    if len(set(v.values())) != 1:
        print("blender-zip.py: versions differ: " + ", ".join(f"{k} {x}" for k, x in v.items()), file=sys.stderr)
        return 2
    names = sorted(f for f in os.listdir(src) if f.endswith(FILES_EXT))
    prefix = "" if kind == "extension" else "skinbake_import/"
    tmp = out + ".tmp"
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for f in names:
            info = zipfile.ZipInfo(prefix + f, DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            with open(os.path.join(src, f), "rb") as fh:
                z.writestr(info, fh.read())
    os.replace(tmp, out)
    print(f"blender-zip.py: {out}: {kind}, {len(names)} files, version {v['schema.VERSION']}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
