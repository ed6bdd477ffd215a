"""The measurement plane: a baked map seen straight on, one render pixel per texel.

A 2 m plane (UVs 0..1, one period of a BAKE_SIZE map) under an orthographic camera that frames
its top-left SIZE × SIZE texels exactly (the texture's region u, v in [0, SIZE / ppu)), its material the
add-on's texture wired into an Emission shader (strength 1, black world, no lights), so each
pixel is the texture's value at the pixel's centre, written as linear float EXR. Cycles' pixel
filter is narrowed to 0.01 px: samples land on the pixel centre, which is a texel centre of the
baked map, so the render should equal the bake texel for texel (tests/blender_scene_test.cpp).
With --route OSL the add-on's OSL shader (no bake) evaluates the texture at each sample instead:
the render should equal the core's own render of the same region (in a Blender without OSL the
script only writes {"cycles_osl": false}).
With --route LIVE (the blend saved as OUT/scene.blend first) Cycles renders the live .stex the
add-on wrote beside the blend, through the OIIO plugin, which the add-on must have put on OIIO's
search path itself; the camera frames the live file's texels (--live-size), and after a tweak
(seed 2, Apply Tweaks) it renders again: OUT/tweaked.exr must show the new live file.

Writes OUT/plane.exr, OUT/plane.stex (the .stex text stored in the blend) and OUT/plane.json.
"""

import os
import shutil
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stochtex_scene as s  # noqa: E402

def extra(parser):
    parser.add_argument("--size", type=int, default=256, help="render pixels per side")
    parser.add_argument("--bake-size", type=int, default=1024, help="texels per side of the baked map")
    parser.add_argument("--route", default="BAKED", choices=["BAKED", "OSL", "LIVE"],
                        help="the add-on's route: a baked map, its OSL shader (no bake; Cycles with OSL), or "
                             "the live .stex read through the OIIO plugin")
    parser.add_argument("--live-size", type=int, default=4096, help="LIVE: level-0 texels per side of the live file")


args = s.arguments(__doc__, extra)
os.makedirs(args.out, exist_ok=True)
if args.route == "OSL" and not getattr(bpy.app.build_options, "cycles_osl", False):
    s.write_report(args.out, "plane.json", {"cycles_osl": False})  # the test says why it skips
    sys.exit(0)
s.install_addon(args.addon)
scene, plane = s.measurement_scene(args.size, args.samples)
settings = {"live_size": args.live_size} if args.route == "LIVE" else {}
if args.route == "LIVE":
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(args.out, "scene.blend"))  # live files go beside it
mat, result, analyse_seconds = s.analyse_onto(plane, args.photo, bake_size=args.bake_size, coordinates="UV",
                                              uv_repeats=1.0, route=args.route, **settings)
assert result == {"FINISHED"}, result

nodes = mat.node_tree.nodes
report = {}
if args.route == "LIVE":
    # Cycles' output shows the live .stex; EEVEE's (the material's own) the baked map.
    cycles_output, eevee_output = mat.node_tree.get_output_node("CYCLES"), mat.node_tree.get_output_node("EEVEE")
    live_image = nodes["stochtex live texture"].node_tree.nodes["stochtex map"].image
    report.update({"cycles_output": cycles_output.name, "eevee_output": eevee_output.name,
                   "eevee_surface": eevee_output.inputs["Surface"].links[0].from_node.name,
                   "live_image_filepath": live_image.filepath, "live_file": bpy.path.abspath(live_image.filepath)})
    s.emission_from(mat, nodes["stochtex live texture"].outputs["Color"], cycles_output)
else:
    s.emission_from(mat, nodes["stochtex texture"].outputs["Color"])
# The top-left 2·SIZE/BAKE_SIZE metres: one pixel per texel of either map, the live file having the
# baked map's texel density (its UV unit holds BAKE_SIZE of the live file's LIVE_SIZE texels, the
# plane's top edge its row LIVE_SIZE - BAKE_SIZE: UVs are scaled about the image's bottom-left).
s.texel_camera(scene, args.size, args.bake_size)

render_seconds = s.render(scene, os.path.join(args.out, "plane.exr"), "OPEN_EXR")
if args.route == "LIVE":  # the live file as each render read it
    shutil.copyfile(report["live_file"], os.path.join(args.out, "live.stex"))
    mat.stochtex.seed = 2
    bpy.context.view_layer.objects.active = plane  # the panel's material: the camera is active now
    assert bpy.ops.stochtex.rebuild() == {"FINISHED"}
    s.emission_from(mat, nodes["stochtex live texture"].outputs["Color"], mat.node_tree.get_output_node("CYCLES"))
    report["tweaked_seconds"] = s.render(scene, os.path.join(args.out, "tweaked.exr"), "OPEN_EXR")
    shutil.copyfile(report["live_file"], os.path.join(args.out, "tweaked.stex"))
with open(os.path.join(args.out, "plane.stex"), "w") as f:
    f.write(mat.stochtex.stex_text.as_string())
report.update({
    "cycles_osl": bool(getattr(bpy.app.build_options, "cycles_osl", False)),
    "analyse_and_bake_seconds": analyse_seconds,
    "render_seconds": render_seconds,
    "stex_text": mat.stochtex.stex_text.name,
})
if args.route in ("BAKED", "LIVE"):
    image = nodes["stochtex texture"].node_tree.nodes["stochtex map"].image
    report.update({"image": image.name, "image_packed": image.packed_file is not None, "image_size": list(image.size)})
else:
    report["shading_system_osl"] = bool(scene.cycles.shading_system)
s.write_report(args.out, "plane.json", report)
