"""The add-on's failure paths and tweaks, headless: each bad input must end in a Blender report
(the operator returns CANCELLED, bpy.ops raises RuntimeError with the report's text) and leave
nothing behind: no new text, image, node group or material data-block, no temporary folder.

Writes OUT/checks.json: one entry per check, {"ok": bool, "detail": str}.
"""

import glob
import importlib
import json
import os
import sys
import tempfile
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stochtex_scene as s  # noqa: E402

args = s.arguments(__doc__)
os.makedirs(args.out, exist_ok=True)
module = s.install_addon(args.addon)  # stochtex (3.4, legacy) or bl_ext.user_default.stochtex (4.2+)
scene = s.empty_scene()
bpy.ops.mesh.primitive_plane_add(size=2.0)
plane = bpy.context.active_object
mat = bpy.data.materials.new("checks")
plane.data.materials.append(mat)
bpy.context.view_layer.objects.active = plane
mat.stochtex.bake_size = 128
checks = {}


def inventory():
    return (len(bpy.data.texts), len(bpy.data.images), len(bpy.data.node_groups), len(bpy.data.materials),
            len(glob.glob(os.path.join(tempfile.gettempdir(), "stochtex-blender-*"))))


def expect_report(name, expected_text, call):
    before = inventory()
    try:
        result = call()
        checks[name] = {"ok": False, "detail": "no error reported; operator returned %s" % result}
        return
    except RuntimeError as error:
        message = str(error)
    after = inventory()
    ok = expected_text in message and after == before and "Traceback" not in message
    checks[name] = {"ok": ok, "detail": "%s | data-blocks and temp folders before %s after %s" % (message.strip(), before, after)}


expect_report("missing photo file", "photo not found", lambda: bpy.ops.stochtex.analyze(filepath="/nonexistent/photo.png"))

not_an_image = os.path.join(args.out, "notes.png")
with open(not_an_image, "w") as f:
    f.write("this is not an image\n")
expect_report("non-image file", "notes.png", lambda: bpy.ops.stochtex.analyze(filepath=not_an_image))

expect_report("no photo chosen", "choose a photo", lambda: bpy.ops.stochtex.analyze())

ghost = bpy.data.images.new("ghost", 4, 4)
ghost.source = "FILE"
ghost.filepath = "/nonexistent/ghost.png"
mat.stochtex.image = ghost
expect_report("image data-block with a missing file", "file not found", lambda: bpy.ops.stochtex.analyze())
mat.stochtex.image = None
bpy.data.images.remove(ghost)

# The preferences live under the add-on's own module name (__package__): a stex path set there
# is the one the operator runs.
preferences = bpy.context.preferences.addons[module].preferences
preferences.stex_path = "/nonexistent/stex"
expect_report("stex path from the preferences", "/nonexistent/stex", lambda: bpy.ops.stochtex.analyze(filepath=args.photo))
preferences.stex_path = ""

# A bake cancelled half-way (what Esc does in the modal operator): the job is killed, and the
# operator's temporary folder is removed with the partial map in it.
stex_cli = importlib.import_module(module + ".stex_cli")  # the installed add-on's own module
work = stex_cli.WorkDir()
stex = stex_cli.find_stex()
stex_cli.run(stex, stex_cli.analyze_args(args.photo, work.file("t.stex"), "wavelet"))
job = stex_cli.StexJob(stex, stex_cli.bake_args(work.file("t.stex"), work.file("big.exr"), 8192))
time.sleep(0.5)
running = job.poll() is None
job.cancel()
left = sorted(os.listdir(work.path))
work.remove()
checks["cancelled bake"] = {"ok": running and "big.exr" not in left and not os.path.exists(work.path),
                            "detail": "running when cancelled: %s; files after cancel: %s; progress seen %.2f"
                                      % (running, left, job.fraction)}

# Auto (the panel's default): the analysis chooses a model and the panel shows which.
result = bpy.ops.stochtex.analyze(filepath=args.photo)
analysable = [m[0] for m in stex_cli.analysable_models(stex_cli.list_models(stex))][1:]
checks["auto shows its choice"] = {
    "ok": result == {"FINISHED"} and mat.stochtex.model == "auto" and mat.stochtex.chosen_model.split("/")[0] in analysable,
    "detail": "%s, model %s, analysed as %r" % (result, mat.stochtex.model, mat.stochtex.chosen_model)}

# Analysis options (the registry's, typed as key=value): an option the model does not take is a
# report naming it; tiling's filter-taps=1 reaches the stored texture.
mat.stochtex.model = "tiling"
mat.stochtex.analysis_options = "J=80"
expect_report("option of another model", "not an option of this model", lambda: bpy.ops.stochtex.analyze(filepath=args.photo))
mat.stochtex.analysis_options = "filter-taps=1, exemplar-size=64"
result = bpy.ops.stochtex.analyze(filepath=args.photo)
stored = json.loads(mat.stochtex.stex_text.as_string()) if result == {"FINISHED"} else {}
checks["analysis options reach the texture"] = {
    "ok": stored.get("model") == "tiling" and stored.get("parameters", {}).get("filter_taps") == 1,
    "detail": "%s, model %s, filter_taps %s" % (result, stored.get("model"), stored.get("parameters", {}).get("filter_taps"))}
mat.stochtex.analysis_options = ""

# A good run, then every tweak and a morph (of the texture with itself, at t = 0.5).
mat.stochtex.model = "wavelet"
result = bpy.ops.stochtex.analyze(filepath=args.photo)
checks["analyse"] = {"ok": result == {"FINISHED"} and mat.stochtex.stex_text is not None, "detail": str(result)}
settings = mat.stochtex
settings.seed = 7
settings.use_histograms = False
settings.band_gains[0] = 0.0
settings.morph_text = settings.stex_text
settings.morph_t = 0.5
result = bpy.ops.stochtex.rebuild()
image = mat.node_tree.nodes["stochtex texture"].node_tree.nodes["stochtex map"].image
checks["tweaks and morph"] = {"ok": result == {"FINISHED"} and image is not None and image.size[0] == 128,
                              "detail": "%s, image %s" % (result, image.name if image else None)}
checks["one map image after rebuild"] = {
    "ok": len([i for i in bpy.data.images if i.name.startswith("concrete")]) == 1,
    "detail": ", ".join(i.name for i in bpy.data.images)}

s.write_report(args.out, "checks.json", checks)
