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
    """Installs and enables the add-on from its zip, as a user would (Preferences > Add-ons > Install)."""
    bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True)
    bpy.ops.preferences.addon_enable(module="stochtex")


def default_cube_material():
    """The factory scene's cube, made active, and its material (the UI-path scripts use them)."""
    cube = bpy.data.objects["Cube"]
    bpy.context.view_layer.objects.active = cube
    return cube.active_material


def empty_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene = bpy.context.scene
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
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
