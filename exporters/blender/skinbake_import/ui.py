"""The add-on / extension user interface: File > Import > skinbake image set."""
import os

import bpy

from .common import SkinbakeError
from .imageset import read_manifest
from .importer import import_set
from .scenejson import apply_scene_json, read_scene_json

try:
    from bpy_extras.io_utils import ImportHelper
except ImportError:             # pragma: no cover - outside Blender
    ImportHelper = object


class IMPORT_OT_skinbake(bpy.types.Operator, ImportHelper):
    """Import a skinbake image set (select its manifest.json); the material goes to the selected meshes"""
    bl_idname = "import_scene.skinbake"
    bl_label = "Import skinbake image set"
    bl_options = {"REGISTER", "UNDO"}
    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="manifest.json", options={"HIDDEN"})
    mode: bpy.props.EnumProperty(
        name="Mode",
        items=(("GENERAL", "General", "Principled BSDF fitted to the bake: any lights, Cycles and EEVEE"),
               ("EXACT", "Exact", "The baked BRDF for every sun, point and spot lamp (one view layer per "
                                  "lamp, summed in the compositor)")),
        default="GENERAL")
    uv_size: bpy.props.FloatProperty(name="UV size [m]", default=0.0, min=0.0,
                                     description="Metres covered by one UV unit (0: measured per object)")
    detail: bpy.props.BoolProperty(name="Detail normal map", default=True)
    generate_uvs: bpy.props.BoolProperty(name="Generate missing UVs", default=False,
                                         description="Smart UV Project on meshes without UVs")
    scene_json: bpy.props.StringProperty(name="Scene (scene.json)", default="", subtype="FILE_PATH",
                                         description="Add the camera and lights of this scene.json "
                                                     "(skinbake scene) as POV-Ray has them; empty: none")

    def execute(self, context):
        obs = [o for o in context.selected_objects if o.type == "MESH"]
        try:
            m = read_manifest(os.path.dirname(self.filepath))
            if self.scene_json:
                apply_scene_json(read_scene_json(bpy.path.abspath(self.scene_json)), context.scene)
            mat = import_set(m, context.scene, obs, self.mode.lower(), no_detail=not self.detail,
                             uv_size=self.uv_size or None, gen_uvs=self.generate_uvs)
        except SkinbakeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"skinbake: {mat.name} on {len(obs)} object(s)")
        return {"FINISHED"}


def _menu(self, context):
    self.layout.operator(IMPORT_OT_skinbake.bl_idname, text="skinbake image set (manifest.json)")


def register():
    bpy.utils.register_class(IMPORT_OT_skinbake)
    bpy.types.TOPBAR_MT_file_import.append(_menu)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_menu)
    bpy.utils.unregister_class(IMPORT_OT_skinbake)
