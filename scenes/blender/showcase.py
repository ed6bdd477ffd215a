"""The showcase: a cube with sharp edges and a sphere wearing the solid texture, on a floor.

Cube and sphere use the add-on's solid route (the solid texture baked onto each object's UVs:
continuous across the cube's edges and the UV seams); the floor the baked 2D map in object
coordinates (metres, box projection). Lit by a sun and a grey sky; Cycles CPU, no denoiser.
Writes OUT/showcase.png and OUT/showcase.json.
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stochtex_scene as s  # noqa: E402


def extra(parser):
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--floor-photo", default="", help="another photo for the floor (default: --photo)")
    parser.add_argument("--map-size", type=int, default=512)


args = s.arguments(__doc__, extra)
os.makedirs(args.out, exist_ok=True)
s.install_addon(args.addon)
scene = s.empty_scene()
s.cycles(scene, args.width, args.height, args.samples)
scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.6, 0.7, 0.85, 1.0)
scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
scene.view_settings.view_transform = "Standard"

timings = {}
bpy.ops.mesh.primitive_plane_add(size=8.0, location=(0, 0, 0))
floor = bpy.context.active_object
_, result, timings["floor_analyse_bake_seconds"] = s.analyse_onto(
    floor, args.floor_photo or args.photo, coordinates="OBJECT", unit_size=1.0, bake_size=args.map_size)
assert result == {"FINISHED"}, result

bpy.ops.mesh.primitive_cube_add(size=1.2, location=(-0.75, 0.2, 0.6), rotation=(0, 0, math.radians(30)))
cube = bpy.context.active_object
_, result, timings["cube_analyse_solid_bake_seconds"] = s.analyse_onto(
    cube, args.photo, route="SOLID", unit_size=0.6, bake_size=args.map_size)
assert result == {"FINISHED"}, result

bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, location=(0.85, -0.35, 0.6), segments=64, ring_count=32)
sphere = bpy.context.active_object
bpy.ops.object.shade_smooth()
_, result, timings["sphere_analyse_solid_bake_seconds"] = s.analyse_onto(
    sphere, args.photo, route="SOLID", unit_size=0.6, bake_size=args.map_size)
assert result == {"FINISHED"}, result

bpy.ops.object.light_add(type="SUN", rotation=(math.radians(50), 0, math.radians(-35)))
bpy.context.active_object.data.energy = 3.0
bpy.ops.object.camera_add(location=(3.4, -4.4, 2.7))
camera = bpy.context.active_object
bpy.ops.object.empty_add(location=(0.0, 0.0, 0.45))
aim = camera.constraints.new("TRACK_TO")
aim.target = bpy.context.active_object
aim.track_axis, aim.up_axis = "TRACK_NEGATIVE_Z", "UP_Y"
camera.data.lens = 40
scene.camera = camera

scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.compression = 100
timings["render_seconds"] = s.render(scene, os.path.join(args.out, "showcase.png"), "PNG")
s.write_report(args.out, "showcase.json", timings)
