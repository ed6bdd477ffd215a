"""Helpers for the Blender scene builders (run inside Blender: blender -b --factory-startup --python X.py -- ...).

No binary .blend in git: every scene is built by these scripts from an empty factory scene.
"""

import argparse
import json
import os
import sys
import time

import bpy


def arguments(description, extra=None):
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--addon", required=True, help="the add-on zip built by cmake (build/addon/stochtex-*.zip)")
    parser.add_argument("--photo", required=True, help="the photo to analyse")
    parser.add_argument("--out", required=True, help="output folder")
    parser.add_argument("--samples", type=int, default=16)
    if extra:
        extra(parser)
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return parser.parse_args(argv)


def install_addon(zip_path):
    """Installs and enables the add-on from its zip, as a user would, and returns its module name.

    Blender 4.2+ installs it as an extension (Preferences > Get Extensions > Install from Disk:
    the manifest is validated, the module is bl_ext.user_default.stochtex); older Blenders use
    the legacy path (Preferences > Add-ons > Install, module stochtex, bl_info)."""
    zip_path = os.path.abspath(zip_path)
    if bpy.app.version >= (4, 2, 0):
        result = bpy.ops.extensions.package_install_files(filepath=zip_path, repo="user_default",
                                                          enable_on_install=True)
        module = "bl_ext.user_default.stochtex"
    else:
        bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
        result = bpy.ops.preferences.addon_enable(module="stochtex")
        module = "stochtex"
    if result != {"FINISHED"} or module not in bpy.context.preferences.addons:
        raise RuntimeError("installing the add-on from %s failed (%s)" % (zip_path, result))
    print("stochtex add-on enabled as %s in Blender %s" % (module, bpy.app.version_string))
    return module


def default_cube_material():
    """The factory scene's cube, made active, and its material (the UI-path scripts use them)."""
    cube = bpy.data.objects["Cube"]
    bpy.context.view_layer.objects.active = cube
    return cube.active_material


def node_material(data_block):
    """Gives a material or world its node tree: Blender 5.0 deprecated use_nodes (every material
    and world has nodes), so it is set only where it still means something."""
    if bpy.app.version < (5, 0, 0):
        data_block.use_nodes = True


def empty_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene = bpy.context.scene
    world = bpy.data.worlds.new("black")
    node_material(world)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    return scene


def cycles(scene, width, height, samples, seed=1):
    """Cycles on the CPU, few samples, no denoiser (Debian's Blender has none), fixed seed."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.seed = seed
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.threads_mode = "AUTO"


def measurement_scene(size, samples):
    """A Cycles scene for texel-exact measurement and a 2 m plane in it (UVs 0..1): size² pixels,
    a 0.01 px pixel filter (every sample at its pixel's centre) and the Standard view transform
    (no tone curve between the texture and the file). Returns (scene, plane)."""
    scene = empty_scene()
    cycles(scene, size, size, samples)
    scene.cycles.filter_width = 0.01
    scene.view_settings.view_transform = "Standard"
    bpy.ops.mesh.primitive_plane_add(size=2.0)
    return scene, bpy.context.active_object


def analyse_onto(obj, photo, **settings):
    """Runs the add-on's analyse operator for obj's material, as the panel's button does."""
    mat = bpy.data.materials.new(obj.name + " material")
    obj.data.materials.append(mat)
    bpy.context.view_layer.objects.active = obj
    # The scene figures measure the wavelet route (addon_checks.py checks Auto's choice).
    settings.setdefault("model", "wavelet")
    for key, value in settings.items():
        setattr(mat.stochtex, key, value)
    start = time.monotonic()
    result = bpy.ops.stochtex.analyze(filepath=photo)
    return mat, result, time.monotonic() - start


def emission_from(mat, color_socket, output=None):
    """Measurement wiring: `color_socket` straight into an Emission shader (strength 1) as the
    surface of `output` (default: the material's first output), so each pixel is the texture's
    value (black world, no lights)."""
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    links.new(color_socket, emission.inputs["Color"])
    output = output or next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
    links.new(emission.outputs[0], output.inputs["Surface"])


def texel_camera(scene, size, texels):
    """An orthographic camera over the 2 m plane (x in [-1, 1] is u in [0, 1], its top edge the
    image's first row) framing its top-left size x size texels of a texels-wide image."""
    half = size / texels
    bpy.ops.object.camera_add(location=(-1 + half, 1 - half, 5), rotation=(0, 0, 0))
    camera = bpy.context.active_object
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = 2 * half
    scene.camera = camera
    return camera


def render(scene, path, file_format):
    scene.render.image_settings.file_format = file_format
    if file_format == "OPEN_EXR":
        scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    start = time.monotonic()
    bpy.ops.render.render(write_still=True)
    return time.monotonic() - start


def write_report(out, name, report):
    with open(os.path.join(out, name), "w") as f:
        json.dump(report, f, indent=2)
