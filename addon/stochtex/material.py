"""Node trees: the texture as a node group, wired into a material (docs/blender.md)."""

import bpy

from . import stex_cli

GROUP_PREFIX = "stochtex "


def _new_socket(group, name, in_out, socket_type):
    if hasattr(group, "interface"):  # Blender 4.0+
        return group.interface.new_socket(name, in_out=in_out, socket_type=socket_type)
    sockets = group.inputs if in_out == "INPUT" else group.outputs
    return sockets.new(socket_type, name)


def ensure_nodes(material):
    """Makes `material` a node material. Blender 5.0 deprecated Material.use_nodes (every
    material has nodes), so it is only set where it still means something."""
    if bpy.app.version < (5, 0, 0):
        material.use_nodes = True


def uses_nodes(material):
    return bpy.app.version >= (5, 0, 0) or material.use_nodes


def set_linear(image):
    """Scene-linear Rec.709, the .stex colour space, under either Blender's name for it."""
    for name in ("Linear Rec.709", "Linear"):
        try:
            image.colorspace_settings.name = name
            return
        except TypeError:
            continue


def baked_group(name, image, box_projection):
    """Group "stochtex NAME": Vector (object metres, or UV × repeats) → the baked map's Color.

    Vector is in metres for object coordinates; one period of the map is period_m metres. For UV
    coordinates the material scales UVs so that one UV unit holds `repeats` periods. Object and
    generated coordinates use box projection (each face takes the map along its dominant axis,
    blended where the normal is between axes): a 2D map cannot be continuous across a sharp
    edge; the OSL route's solid texture is.
    """
    group = bpy.data.node_groups.get(GROUP_PREFIX + name)
    if group is None:
        group = bpy.data.node_groups.new(GROUP_PREFIX + name, "ShaderNodeTree")
        _new_socket(group, "Vector", "INPUT", "NodeSocketVector")
        _new_socket(group, "Period", "INPUT", "NodeSocketFloat")
        _new_socket(group, "Color", "OUTPUT", "NodeSocketColor")
    nodes, links = group.nodes, group.links
    nodes.clear()
    inputs = nodes.new("NodeGroupInput")
    outputs = nodes.new("NodeGroupOutput")
    divide = nodes.new("ShaderNodeVectorMath")
    divide.operation = "DIVIDE"
    combine = nodes.new("ShaderNodeCombineXYZ")
    texture = nodes.new("ShaderNodeTexImage")
    texture.name = texture.label = "stochtex map"
    texture.image = image
    texture.extension = "REPEAT"   # the map is one seamless period
    texture.interpolation = "Linear"
    if box_projection:
        texture.projection = "BOX"
        texture.projection_blend = 0.2
    links.new(inputs.outputs["Period"], combine.inputs[0])
    links.new(inputs.outputs["Period"], combine.inputs[1])
    links.new(inputs.outputs["Period"], combine.inputs[2])
    links.new(inputs.outputs["Vector"], divide.inputs[0])
    links.new(combine.outputs[0], divide.inputs[1])
    links.new(divide.outputs[0], texture.inputs["Vector"])
    links.new(texture.outputs["Color"], outputs.inputs["Color"])
    for i, node in enumerate((inputs, combine, divide, texture, outputs)):
        node.location = (i * 220 - 440, 0)
    return group


def _coordinates(settings):
    """A solid map lives on the object's UV layout; the other routes use the panel's choice."""
    return "UV" if settings.route == "SOLID" else settings.coordinates


def _texture_input(nodes, settings, x):
    """The coordinate socket for the texture, in the group's units (metres or UV × repeats)."""
    coordinates = nodes.new("ShaderNodeTexCoord")
    coordinates.location = (x - 220, 0)
    socket = {"UV": "UV", "OBJECT": "Object", "GENERATED": "Generated"}[_coordinates(settings)]
    return coordinates.outputs[socket]


def build_material(material, settings, name, image=None, period=1.0, osl_text=None, unit_size_m=1.0, live=None):
    """(Re)builds `material`'s nodes: coordinates → texture → Principled Base Color → output.

    period: the baked map's period in the coordinates' units (map_period). live: (the .stex image,
    its period) for the Live route, whose texture feeds a Cycles-only output (_live_output).
    Everything else in the material is left alone, except nodes this add-on made before
    (named "stochtex ..."), which are replaced.
    """
    ensure_nodes(material)
    nodes, links = material.node_tree.nodes, material.node_tree.links
    for node in [n for n in nodes if n.name.startswith("stochtex")]:
        nodes.remove(node)
    bsdf = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        bsdf = nodes.new("ShaderNodeBsdfPrincipled")
        output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL"), None) or nodes.new("ShaderNodeOutputMaterial")
        links.new(bsdf.outputs[0], output.inputs["Surface"])
    x = bsdf.location.x - 300
    coordinates = _texture_input(nodes, settings, x - 220)
    coordinates.node.name = "stochtex coordinates"
    if osl_text is not None:
        node = nodes.new("ShaderNodeScript")
        node.mode = "INTERNAL"
        node.script = osl_text
        compile_script(node)
        # The tiling shader has no Solid.
        if "Solid" in node.inputs:
            node.inputs["Solid"].default_value = 1 if settings.solid else 0
        if "Scale" in node.inputs:
            scale = 1.0 / unit_size_m if _coordinates(settings) == "OBJECT" else settings.uv_repeats
            node.inputs["Scale"].default_value = scale
        if "Vector" in node.inputs:
            links.new(coordinates, node.inputs["Vector"])
    else:
        node = _texture_node(nodes, links, name, image, settings, coordinates, period)
    node.name = "stochtex texture"
    node.label = "stochtex " + name
    node.location = (x, bsdf.location.y)
    coordinates.node.location = (x - 240, bsdf.location.y)
    if "Color" in node.outputs:
        links.new(node.outputs["Color"], bsdf.inputs["Base Color"])
    if live is not None:
        _live_output(material, bsdf, _texture_node(nodes, links, name + " live", live[0], settings, coordinates, live[1]))
    return node


def map_period(settings, texels, texture_units, unit_size_m, bake_size):
    """The period of a map of `texels` texels covering `texture_units` texture units, in the
    units of the material's coordinates: metres for object coordinates; for UV and generated
    coordinates a baked map of bake_size texels spans 1 / repeats units, and a larger map (the
    Live route's .stex) spans proportionally more at the same texel density. A solid map
    covers the UV square once."""
    if settings.route == "SOLID":
        return 1.0
    if _coordinates(settings) == "OBJECT":
        return texture_units * unit_size_m
    return texels / (bake_size * settings.uv_repeats)


def _texture_node(nodes, links, name, image, settings, coordinates, period_in_units):
    node = nodes.new("ShaderNodeGroup")
    node.node_tree = baked_group(name, image, _coordinates(settings) != "UV")
    links.new(coordinates, node.inputs["Vector"])
    node.inputs["Period"].default_value = period_in_units
    return node


def _live_output(material, bsdf, texture):
    """The Live route's Cycles-only branch: a copy of the Principled BSDF (same inputs and
    links) whose Base Color is the live .stex, into a Material Output targeted at Cycles. An
    output with a target outranks the "All" one for that renderer, so Cycles renders the .stex
    through the OIIO plugin while EEVEE and the viewport — whose image reader knows no plugins —
    keep the baked map of the material's own output."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture.name = "stochtex live texture"
    texture.label = texture.node_tree.name
    live_bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    live_bsdf.name = live_bsdf.label = "stochtex live BSDF"
    for attribute in ("distribution", "subsurface_method"):
        setattr(live_bsdf, attribute, getattr(bsdf, attribute))
    for socket, target in zip(bsdf.inputs, live_bsdf.inputs):  # one node type: the same sockets
        if socket.is_linked:
            links.new(socket.links[0].from_socket, target)
        elif hasattr(socket, "default_value"):
            target.default_value = socket.default_value
    links.new(texture.outputs["Color"], live_bsdf.inputs["Base Color"])
    output = nodes.new("ShaderNodeOutputMaterial")
    output.name = output.label = "stochtex live output"
    output.target = "CYCLES"
    links.new(live_bsdf.outputs[0], output.inputs["Surface"])
    own = next((n for n in nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output and n != output), None)
    if own is not None:  # the material's displacement and volume apply in Cycles too
        for socket_name in ("Volume", "Displacement"):
            if own.inputs[socket_name].is_linked:
                links.new(own.inputs[socket_name].links[0].from_socket, output.inputs[socket_name])
    texture.location = (bsdf.location.x - 300, bsdf.location.y - 700)
    live_bsdf.location = (bsdf.location.x, bsdf.location.y - 700)
    output.location = (bsdf.location.x + 300, bsdf.location.y - 700)


def compile_script(node):
    """Compiles a Script node's shader and makes its sockets, as its Update button does.

    Blender compiles a script when the node editor asks (the button, or editing the text
    there); a script node made from Python, from an operator or in the background, has no
    sockets until then. Cycles' own compile is asked directly; its errors become a StexError."""
    try:
        import cycles.osl  # Cycles' add-on: present wherever Cycles is
    except ImportError:
        raise stex_cli.StexError("Cycles is not available: the OSL route needs it") from None
    errors = []
    ok = cycles.osl.update_script_node(node, lambda kind, text: errors.append(text) if "ERROR" in kind else None)
    if not ok or "Color" not in node.outputs:
        raise stex_cli.StexError("the OSL shader does not compile (%s); the console shows the compiler's messages"
                                 % ("; ".join(errors) or "no Color output"))


def bake_positions(context, obj, mat, size, path):
    """Cycles bakes obj's object-space positions (metres) onto its UV map: a float image whose
    texels hold the surface point they show (the bake margin extends each UV island by a few
    texels, so bilinear lookups at island borders stay on the surface). The material and the
    render settings are restored afterwards; the core then evaluates the solid texture at each
    texel's position."""
    scene = context.scene
    saved = (scene.render.engine, scene.cycles.samples, scene.render.bake.margin, scene.cycles.use_denoising)
    image = bpy.data.images.new("stochtex positions", size, size, alpha=True, float_buffer=True)
    image.colorspace_settings.is_data = True
    # Opaque: Blender keeps float images premultiplied, so alpha 0 would zero the positions.
    image.generated_color = (0.0, 0.0, 0.0, 1.0)
    used_nodes = uses_nodes(mat)
    ensure_nodes(mat)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    outputs = [n for n in nodes if n.type == "OUTPUT_MATERIAL"]
    active_output = next((n for n in outputs if n.is_active_output), None)
    active_node = nodes.active
    temporary = [nodes.new("ShaderNodeTexCoord"), nodes.new("ShaderNodeEmission"),
                 nodes.new("ShaderNodeOutputMaterial"), nodes.new("ShaderNodeTexImage")]
    coordinates, emission, output, target = temporary
    links.new(coordinates.outputs["Object"], emission.inputs["Color"])
    links.new(emission.outputs[0], output.inputs["Surface"])
    output.is_active_output = True
    target.image = image
    nodes.active = target
    selection = [o for o in context.view_layer.objects if o.select_get()]
    try:
        for o in selection:
            o.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        scene.render.engine = "CYCLES"
        scene.cycles.samples = 1
        scene.cycles.use_denoising = False  # Debian's Cycles has no denoiser: with it on, bakes are empty
        scene.render.bake.margin = 4
        try:
            bpy.ops.object.bake(type="EMIT", use_clear=True, target="IMAGE_TEXTURES")
        except RuntimeError as error:
            raise stex_cli.StexError("baking the surface positions of '%s' failed: %s" % (obj.name, error)) from None
        image.filepath_raw = path
        image.file_format = "OPEN_EXR"
        image.save()
    finally:
        for node in temporary:
            nodes.remove(node)
        if active_output is not None:
            active_output.is_active_output = True
        nodes.active = active_node
        obj.select_set(False)
        for o in selection:
            o.select_set(True)
        scene.render.engine, scene.cycles.samples, scene.render.bake.margin, scene.cycles.use_denoising = saved
        if not used_nodes:
            mat.use_nodes = False
        bpy.data.images.remove(image)
