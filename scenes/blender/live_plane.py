"""Cycles renders a .stex live: an Image Texture whose file is the .stex itself, read through the
stex.imageio OIIO plugin (no bake). The plugin must be on OIIO's search path in Blender's
environment (OPENIMAGEIO_PLUGIN_PATH for OIIO 3.x, OIIO_LIBRARY_PATH for 2.x: the test sets both).

Two views of the same 2 m plane (UVs 0..1 = the .stex's whole level 0, W x W texels):
- straight on: an orthographic camera framing its top-left SIZE x SIZE texels, one render pixel
  per texel, Closest interpolation, the texture into an Emission shader (black world), Cycles'
  pixel filter 0.01 px: each pixel should be one level-0 texel (OUT/live.exr);
- receding (--receding): a perspective camera low over the plane, Cubic->Linear interpolation,
  so Cycles 5.2's texture cache reads fine levels near and coarse ones far (OUT/receding.exr).

Writes OUT/live.json (render seconds, Blender version).
"""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stochtex_scene as s  # noqa: E402


def extra(parser):
    parser.add_argument("--stex", required=True, help="the .stex file the Image Texture reads")
    parser.add_argument("--texels", type=int, required=True, help="the .stex's level-0 width (its image block)")
    parser.add_argument("--size", type=int, default=128, help="render pixels per side")
    parser.add_argument("--receding", action="store_true", help="also render the receding view")


args = s.arguments(__doc__, extra)
os.makedirs(args.out, exist_ok=True)
scene, plane = s.measurement_scene(args.size, args.samples)
mat = bpy.data.materials.new("live stex")
plane.data.materials.append(mat)
if bpy.app.version < (5, 0, 0):  # 5.0 deprecated use_nodes: every material has nodes
    mat.use_nodes = True
nodes = mat.node_tree.nodes
image = bpy.data.images.load(os.path.abspath(args.stex))  # Blender's own reader logs "unknown format": fine
image.colorspace_settings.name = "Non-Color"  # the plugin's texels are linear Rec.709 already
tex = nodes.new("ShaderNodeTexImage")
tex.image = image
tex.interpolation = "Closest"
s.emission_from(mat, tex.outputs["Color"])
camera = s.texel_camera(scene, args.size, args.texels)
report = {"blender": bpy.app.version_string,
          "live_seconds": s.render(scene, os.path.join(args.out, "live.exr"), "OPEN_EXR")}

if args.receding:
    # Eye 30 cm above the plane, 20 cm before its near edge, looking 20° down across it to the
    # horizon: the footprint grows with distance, from level ~5 near to the coarsest levels far.
    tex.interpolation = "Linear"
    camera.data.type = "PERSP"
    camera.data.lens = 50
    camera.location = (0.0, -1.2, 0.3)
    camera.rotation_euler = (1.2217, 0.0, 0.0)
    report["receding_seconds"] = s.render(scene, os.path.join(args.out, "receding.png"), "PNG")
with open("/proc/self/status") as status:  # the process' peak resident memory (Linux)
    report["peak_rss_mb"] = next(int(line.split()[1]) for line in status if line.startswith("VmHWM")) / 1024
s.write_report(args.out, "live.json", report)
