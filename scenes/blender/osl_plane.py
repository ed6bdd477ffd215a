"""OSL shaders through Cycles' own OSL (tests/cycles_osl_test.cpp; docs/osl.md): each shader of a
job list is compiled from its file by a Script node (External, as an artist links a `.osl`
file), and, where the job asks, rendered on the measurement plane.

The plane covers x, y in [0, 1] (z = 0) and an orthographic camera straight above frames it
exactly: SIZE × SIZE pixels, pixel (i, j) (row j from the top) centred on
x = (i + ½) / SIZE, y = 1 − (j + ½) / SIZE, and Cycles' ray differentials give every shading
point Dx(P) = (1 / SIZE, 0, 0), Dy(P) = (0, ±1 / SIZE, 0) (the "footprint" job renders them so
the test checks rather than assumes it). Vector is the Geometry node's Position (world P with
its derivatives), times the shader's Scale. The shader's output goes straight into an Emission
shader (strength 1, black world), the pixel filter is 0.01 px wide (samples at pixel centres),
the view transform Standard and the file float EXR: each pixel is the shader's value at its centre.

Jobs (JSON list): {"name", "osl" (file), "output" (socket), "inputs" ({socket: value}),
"render" (bool)}. Writes OUT/<name>.exr per rendered job and OUT/osl_plane.json: {"blender":
version, "cycles_osl": bool, "jobs": {name: {"compiled": bool, "messages": the compiler's and
Cycles' output, "render_seconds": …}}}. A Blender without OSL runs no job.
"""

import argparse
import json
import os
import sys
import tempfile
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stochtex_scene as s  # noqa: E402


def captured(call):
    """Runs call() with the process's stdout and stderr (file descriptors 1 and 2, where OSL's
    compiler writes) sent to a file; returns (call's result, what was written)."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2)
    with tempfile.TemporaryFile(mode="w+") as sink:
        os.dup2(sink.fileno(), 1)
        os.dup2(sink.fileno(), 2)
        try:
            result = call()
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
        sink.seek(0)
        return result, sink.read()


def compile_script(node, path):
    """Cycles' own compile of an external script (what the node's Update button runs): OSL's
    compiler in-process, then the sockets from the compiled parameters."""
    import cycles.osl
    reports = []
    node.mode = "EXTERNAL"
    node.filepath = path
    ok, output = captured(lambda: cycles.osl.update_script_node(node, lambda kind, text: reports.append(text)))
    return bool(ok), (output + "\n".join(reports)).strip()


parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--jobs", required=True)
parser.add_argument("--out", required=True)
parser.add_argument("--size", type=int, default=128)
parser.add_argument("--samples", type=int, default=1)
args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
os.makedirs(args.out, exist_ok=True)
with open(args.jobs) as f:
    jobs = json.load(f)

has_osl = bool(getattr(bpy.app.build_options, "cycles_osl", False))
print("osl_plane: cycles_osl %s in Blender %s" % (has_osl, bpy.app.version_string))
if not has_osl:
    jobs = []

scene = s.empty_scene()
s.cycles(scene, args.size, args.size, args.samples)
scene.cycles.shading_system = True  # OSL (CPU only)
scene.cycles.filter_width = 0.01
scene.view_settings.view_transform = "Standard"
bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.5, 0.5, 0.0))
plane = bpy.context.active_object
bpy.ops.object.camera_add(location=(0.5, 0.5, 1.0), rotation=(0.0, 0.0, 0.0))
camera = bpy.context.active_object
camera.data.type = "ORTHO"
camera.data.ortho_scale = 1.0
scene.camera = camera

report = {}
for job in jobs:
    mat = bpy.data.materials.new(job["name"])
    s.node_material(mat)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    for node in list(nodes):
        nodes.remove(node)
    script = nodes.new("ShaderNodeScript")
    ok, messages = compile_script(script, job["osl"])
    entry = {"compiled": ok and job["output"] in script.outputs, "messages": messages}
    if ok and job["output"] not in script.outputs:
        entry["messages"] += "\nno output %r (outputs: %s)" % (job["output"], [o.name for o in script.outputs])
    if entry["compiled"] and job.get("render"):
        if "Vector" in script.inputs:
            links.new(nodes.new("ShaderNodeNewGeometry").outputs["Position"], script.inputs["Vector"])
        for name, value in job.get("inputs", {}).items():
            script.inputs[name].default_value = value
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Strength"].default_value = 1.0
        links.new(script.outputs[job["output"]], emission.inputs["Color"])
        output = nodes.new("ShaderNodeOutputMaterial")
        links.new(emission.outputs[0], output.inputs["Surface"])
        plane.data.materials.clear()
        plane.data.materials.append(mat)
        seconds, log = captured(lambda: s.render(scene, os.path.join(args.out, job["name"] + ".exr"), "OPEN_EXR"))
        entry["render_seconds"] = seconds
        if "error" in log.lower():
            entry["messages"] += "\n" + log
    report[job["name"]] = entry
    print("osl_plane: %s compiled %s%s" % (job["name"], entry["compiled"],
                                           ", rendered in %.2f s" % entry["render_seconds"] if "render_seconds" in entry else ""))

s.write_report(args.out, "osl_plane.json", {"blender": "Blender " + bpy.app.version_string, "cycles_osl": has_osl,
                                            "jobs": report})
