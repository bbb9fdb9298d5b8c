"""Node-tree helpers: sockets looked up under their names in every Blender version, a small
builder for shader trees, and the stamp every skinbake material carries."""
import bpy

from .schema import VERSION


def sock(sockets, *names):
    """The first socket found under any of NAMES (names differ between Blender 3.x and 4.x)."""
    for n in names:
        if n in sockets:
            return sockets[n]
    return None


class Tree:
    def __init__(self, mat, keep=False):
        """A builder on MAT's node tree, emptied first unless KEEP."""
        mat.use_nodes = True
        self.nt = mat.node_tree
        if not keep:
            self.nt.nodes.clear()

    def node(self, kind, loc, label=None, **props):
        n = self.nt.nodes.new(kind)
        n.location = loc
        if label:
            n.label = label
        for k, v in props.items():
            setattr(n, k, v)
        return n

    def link(self, src, dst):
        self.nt.links.new(src, dst)

    def _in(self, n, i, x):
        if isinstance(x, bpy.types.NodeSocket):
            self.link(x, n.inputs[i])
        else:
            n.inputs[i].default_value = x

    def math(self, op, a, b=0.0, c=None, loc=(0, 0), clamp=False):
        n = self.node("ShaderNodeMath", loc, operation=op, use_clamp=clamp)
        self._in(n, 0, a)
        self._in(n, 1, b)
        if c is not None:
            self._in(n, 2, c)
        return n.outputs[0]

    def vmath(self, op, a, b=None, loc=(0, 0), scale=None):
        n = self.node("ShaderNodeVectorMath", loc, operation=op)
        self._in(n, 0, a)
        if b is not None:
            self._in(n, 1, b)
        if scale is not None:
            self._in(n, n.inputs.find("Scale"), scale)
        return n.outputs["Value" if op in ("DOT_PRODUCT", "LENGTH") else "Vector"]

    def xyz(self, x, y, z, loc, label=None):
        n = self.node("ShaderNodeCombineXYZ", loc, label)
        for i, v in enumerate((x, y, z)):
            self._in(n, i, v)
        return n.outputs["Vector"]

    def mix(self, a, b, f, loc):
        """(1 - f) a + f b on colours (f in [0, 1]; values are not clamped)."""
        n = self.node("ShaderNodeMix", loc, data_type="RGBA", blend_type="MIX")
        self._in(n, 0, f)
        self._in(n, 6, a)
        self._in(n, 7, b)
        return n.outputs[2]

    def attr(self, kind, name, loc, label=None):
        return self.node("ShaderNodeAttribute", loc, label or name, attribute_type=kind, attribute_name=name)

    def tex(self, img, vector, loc, extension="REPEAT", label=None, interpolation="Linear"):
        t = self.node("ShaderNodeTexImage", loc, label, image=img, interpolation=interpolation,
                      extension=extension)
        if vector is not None:
            self.link(vector, t.inputs["Vector"])
        return t


def stamp(mat, m, mode):
    mat["skinbake_importer"] = VERSION
    mat["skinbake_format_version"] = m["format_version"]
    mat["skinbake_mode"] = mode
    mat["skinbake_image_set"] = m["_dir"]
