# Test helper, run inside Blender (or bpy): install the importer the way a user does and list
# its operators.
#   blender -b --factory-startup --python-exit-code 1 --python blender_package.py -- EXT.zip ADDON.zip MANIFEST
# Blender 4.2+ installs EXT.zip as an extension (user_default repository), older ones ADDON.zip
# as a legacy add-on; both into the user resources that BLENDER_USER_RESOURCES (4.2+) or
# BLENDER_USER_SCRIPTS (3.x) name.  Prints "SKINBAKE_PACKAGE <kind> <module>", one
# "SKINBAKE_OPERATOR <idname>" per operator class of the package, then runs File > Import >
# skinbake image set on the default cube with MANIFEST and prints "SKINBAKE_IMPORT <result> <material>".
import sys

import bpy

ext_zip, addon_zip, manifest = sys.argv[sys.argv.index("--") + 1:][:3]
if bpy.app.version >= (4, 2, 0):
    kind = "extension"
    r = bpy.ops.extensions.package_install_files(filepath=ext_zip, repo="user_default", enable_on_install=True)
    module = "bl_ext.user_default.skinbake_import"
else:
    kind = "add-on"
    r = bpy.ops.preferences.addon_install(filepath=addon_zip)
    module = "skinbake_import"
    bpy.ops.preferences.addon_enable(module=module)
print("SKINBAKE_INSTALL", ",".join(sorted(r)))
pkg = sys.modules.get(module)
if pkg is None:
    raise SystemExit(f"{module} is not loaded after installing the {kind}")
print("SKINBAKE_PACKAGE", kind, module, pkg.__version__)
ops = []
for name in sorted(dir(pkg.ui)):
    c = getattr(pkg.ui, name)
    if isinstance(c, type) and issubclass(c, bpy.types.Operator) and c is not bpy.types.Operator:
        cat, op = c.bl_idname.split(".")
        if not hasattr(getattr(bpy.ops, cat), op):
            raise SystemExit(f"operator {c.bl_idname} of {module} is not registered")
        ops.append(c.bl_idname)
        print("SKINBAKE_OPERATOR", c.bl_idname, "-", c.bl_label)
if not ops:
    raise SystemExit(f"{module} has no operators")
cube = bpy.data.objects.get("Cube")
for o in bpy.context.view_layer.objects:
    o.select_set(o == cube)
r = bpy.ops.import_scene.skinbake(filepath=manifest, mode="GENERAL", detail=False)
print("SKINBAKE_IMPORT", ",".join(sorted(r)), cube.active_material.name.replace(" ", "_"))
