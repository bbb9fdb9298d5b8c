"""The compositor of the exact mode: the sum of the per-lamp view layers."""
from .common import PREFIX


def compositor_sum(scene, source, layers):
    """Compositor nodes adding the Image outputs of LAYERS; what the SOURCE layer fed now gets the sum."""
    scene.use_nodes = True
    scene.render.use_compositing = True
    nt = scene.node_tree
    for n in [n for n in nt.nodes if n.name.startswith(PREFIX)]:
        nt.nodes.remove(n)
    comp = next((n for n in nt.nodes if n.type == "COMPOSITE"), None)
    if comp is None:
        comp = nt.nodes.new("CompositorNodeComposite")
        comp.location = (600, 0)
    if not layers:
        return
    total = None
    for i, name in enumerate(layers):
        rl = nt.nodes.new("CompositorNodeRLayers")
        rl.name = f"{PREFIX} layer {i}"
        rl.label = name
        rl.layer = name
        rl.location = (-600, -300 * i)
        if total is None:
            total = rl.outputs["Image"]
            continue
        add = nt.nodes.new("CompositorNodeMixRGB")
        add.name = f"{PREFIX} sum {i}"
        add.blend_type = "ADD"
        add.use_alpha = False
        add.inputs[0].default_value = 1.0
        add.location = (-300 + 150 * i, -300 * i)
        nt.links.new(total, add.inputs[1])
        nt.links.new(rl.outputs["Image"], add.inputs[2])
        total = add.outputs["Image"]
    relinked = False
    for link in list(nt.links):
        fn = link.from_node
        if fn.type == "R_LAYERS" and not fn.name.startswith(PREFIX) and fn.layer == source.name \
                and link.from_socket.name == "Image":
            nt.links.new(total, link.to_socket)
            relinked = True
    if not relinked:
        nt.links.new(total, comp.inputs["Image"])
