"""The compositor of the exact mode: the sum of the per-lamp view layers.

Blender up to 4.x keeps the compositor in scene.node_tree (output: a Composite node, sums with
MixRGB); 5.0 made it a node group, scene.compositing_node_group (output: the group's Image
output, sums with the Mix node)."""
import bpy

from .common import PREFIX


def _tree(scene):
    """(compositor node tree, the input socket that is the final image)."""
    scene.render.use_compositing = True
    if hasattr(scene, "node_tree"):                      # up to 4.x
        scene.use_nodes = True
        nt = scene.node_tree
        comp = next((n for n in nt.nodes if n.type == "COMPOSITE"), None)
        if comp is None:
            comp = nt.nodes.new("CompositorNodeComposite")
            comp.location = (600, 0)
        return nt, comp.inputs["Image"]
    nt = scene.compositing_node_group
    if nt is None:
        nt = bpy.data.node_groups.new(PREFIX + " compositor", "CompositorNodeTree")
        scene.compositing_node_group = nt
    if not any(s.in_out == "OUTPUT" and s.name == "Image" for s in nt.interface.items_tree
               if s.item_type == "SOCKET"):
        nt.interface.new_socket("Image", in_out="OUTPUT", socket_type="NodeSocketColor")
    out = next((n for n in nt.nodes if n.type == "GROUP_OUTPUT" and n.is_active_output), None)
    if out is None:
        out = nt.nodes.new("NodeGroupOutput")
        out.location = (600, 0)
    return nt, out.inputs["Image"]


def _add(nt, a, b, i):
    """A node giving a + b (colours)."""
    if hasattr(bpy.types, "CompositorNodeMixRGB"):       # up to 4.x
        add = nt.nodes.new("CompositorNodeMixRGB")
        add.blend_type = "ADD"
        add.use_alpha = False
        add.inputs[0].default_value = 1.0
        ia, ib, out = add.inputs[1], add.inputs[2], add.outputs["Image"]
    else:
        add = nt.nodes.new("ShaderNodeMix")
        add.data_type = "RGBA"
        add.blend_type = "ADD"
        add.clamp_result = False
        add.inputs[0].default_value = 1.0
        ia, ib, out = add.inputs[6], add.inputs[7], add.outputs[2]
    add.name = f"{PREFIX} sum {i}"
    add.location = (-300 + 150 * i, -300 * i)
    nt.links.new(a, ia)
    nt.links.new(b, ib)
    return out


def compositor_sum(scene, source, layers):
    """Compositor nodes adding the Image outputs of LAYERS; what the SOURCE layer fed now gets the sum."""
    nt, final = _tree(scene)
    for n in [n for n in nt.nodes if n.name.startswith(PREFIX)]:
        nt.nodes.remove(n)
    if not layers:
        return
    total = None
    for i, name in enumerate(layers):
        rl = nt.nodes.new("CompositorNodeRLayers")
        rl.name = f"{PREFIX} layer {i}"
        rl.label = name
        rl.layer = name
        rl.location = (-600, -300 * i)
        total = rl.outputs["Image"] if total is None else _add(nt, total, rl.outputs["Image"], i)
    relinked = False
    for link in list(nt.links):
        fn = link.from_node
        if fn.type == "R_LAYERS" and not fn.name.startswith(PREFIX) and fn.layer == source.name \
                and link.from_socket.name == "Image":
            nt.links.new(total, link.to_socket)
            relinked = True
    if not relinked:
        nt.links.new(total, final)
