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

Writes OUT/plane.exr, OUT/plane.stex (the .stex text stored in the blend) and OUT/plane.json.
"""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stochtex_scene as s  # noqa: E402

def extra(parser):
    parser.add_argument("--size", type=int, default=256, help="render pixels per side")
    parser.add_argument("--bake-size", type=int, default=1024, help="texels per side of the baked map")
    parser.add_argument("--route", default="BAKED", choices=["BAKED", "OSL"],
                        help="the add-on's route: a baked map, or its OSL shader (no bake; Cycles with OSL)")


args = s.arguments(__doc__, extra)
os.makedirs(args.out, exist_ok=True)
if args.route == "OSL" and not getattr(bpy.app.build_options, "cycles_osl", False):
    s.write_report(args.out, "plane.json", {"cycles_osl": False})  # the test says why it skips
    sys.exit(0)
s.install_addon(args.addon)
scene = s.empty_scene()
s.cycles(scene, args.size, args.size, args.samples)
scene.cycles.filter_width = 0.01
scene.view_settings.view_transform = "Standard"

bpy.ops.mesh.primitive_plane_add(size=2.0)
plane = bpy.context.active_object
mat, result, analyse_seconds = s.analyse_onto(plane, args.photo, bake_size=args.bake_size, coordinates="UV",
                                              uv_repeats=1.0, route=args.route)
assert result == {"FINISHED"}, result

nodes = mat.node_tree.nodes
s.emission_from(mat, nodes["stochtex texture"].outputs["Color"])
s.texel_camera(scene, args.size, args.bake_size)  # the top-left 2·SIZE/BAKE_SIZE metres

render_seconds = s.render(scene, os.path.join(args.out, "plane.exr"), "OPEN_EXR")
with open(os.path.join(args.out, "plane.stex"), "w") as f:
    f.write(mat.stochtex.stex_text.as_string())
report = {
    "cycles_osl": bool(getattr(bpy.app.build_options, "cycles_osl", False)),
    "analyse_and_bake_seconds": analyse_seconds,
    "render_seconds": render_seconds,
    "stex_text": mat.stochtex.stex_text.name,
}
if args.route == "BAKED":
    image = nodes["stochtex texture"].node_tree.nodes["stochtex map"].image
    report.update({"image": image.name, "image_packed": image.packed_file is not None, "image_size": list(image.size)})
else:
    report["shading_system_osl"] = bool(scene.cycles.shading_system)
s.write_report(args.out, "plane.json", report)
