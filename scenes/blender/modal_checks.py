"""The add-on's interactive path, in Blender's real UI (needs a display: Xvfb; and
--enable-event-simulate): the operator invoked as a button does (INVOKE_DEFAULT) runs modal, the
UI keeps running while stex bakes, Esc cancels and leaves nothing, a finished run is one undo step.

Writes OUT/modal.json: one entry per check, {"ok": bool, "detail": str}; then quits.
"""

import glob
import os
import sys
import tempfile
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stochtex_scene as s  # noqa: E402

args = s.arguments(__doc__)
os.makedirs(args.out, exist_ok=True)
s.install_addon(args.addon)
mat = s.default_cube_material()
state = {"material": mat.name}
photo = os.path.abspath(args.photo)
checks = {}


def inventory():
    return (len(bpy.data.texts), len(bpy.data.images), len(bpy.data.node_groups),
            len(glob.glob(os.path.join(tempfile.gettempdir(), "stochtex-blender-*"))))


def ui_context():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    return window, dict(window=window, area=area, region=region)


def start_cancelled_bake():
    window, override = ui_context()
    state["before"] = inventory()
    mat.stochtex.bake_size = 8192  # long enough to cancel half-way
    mat.stochtex.model = "wavelet"  # a quick analysis: Escape lands in the bake
    with bpy.context.temp_override(**override):
        state["invoke"] = bpy.ops.stochtex.analyze("INVOKE_DEFAULT", filepath=photo)
    state["ticks"] = []
    bpy.app.timers.register(tick, first_interval=0.05)
    bpy.app.timers.register(lambda: press_escape(window), first_interval=3.0)
    return None


def tick():
    """A UI timer: it only fires while Blender's event loop runs, i.e. the UI is not frozen."""
    state["ticks"].append(time.monotonic())
    return 0.05 if len(state["ticks"]) < 200 else None


def press_escape(window):
    during = inventory()
    window.event_simulate(type="ESC", value="PRESS")
    window.event_simulate(type="ESC", value="RELEASE")
    bpy.app.timers.register(lambda: after_cancel(during), first_interval=1.0)
    return None


def after_cancel(during):
    ticks = state["ticks"]
    gaps = [b - a for a, b in zip(ticks, ticks[1:])]
    checks["invoked modal"] = {"ok": state["invoke"] == {"RUNNING_MODAL"}, "detail": str(state["invoke"])}
    # An idle machine ticks ~60 times in 3 s; under load (2 cores shared with the bake, Xvfb's
    # software OpenGL drawing the UI) fewer. A frozen UI would not tick at all until the bake
    # (tens of seconds at 8192²) ended: one gap as long as the bake.
    checks["UI runs during the bake"] = {
        "ok": len(ticks) >= 5 and max(gaps) < 2.0,
        "detail": "%d UI timer ticks in 3 s, longest gap %.3f s" % (len(ticks), max(gaps) if gaps else -1)}
    after = inventory()
    checks["Esc cancels and leaves nothing"] = {
        "ok": after == state["before"] and during[3] == state["before"][3] + 1,
        "detail": "texts, images, groups, temp folders: before %s, during %s, after %s" % (state["before"], during, after)}
    start_finished_run()
    return None


def start_finished_run():
    _, override = ui_context()
    mat.stochtex.bake_size = 256
    state["before"] = inventory()
    with bpy.context.temp_override(**override):
        bpy.ops.ed.undo_push(message="before stochtex")
        bpy.ops.stochtex.analyze("INVOKE_DEFAULT", filepath=photo)
    state["started"] = time.monotonic()
    bpy.app.timers.register(wait_for_finish, first_interval=0.2)


def wait_for_finish():
    if mat.stochtex.stex_text is None and time.monotonic() - state["started"] < 60:
        return 0.2
    made = inventory()
    checks["finishes and builds the material"] = {
        "ok": mat.stochtex.stex_text is not None and "stochtex texture" in mat.node_tree.nodes,
        "detail": "after %.1f s: %s" % (time.monotonic() - state["started"], made)}
    _, override = ui_context()
    with bpy.context.temp_override(**override):
        bpy.ops.ed.undo()
    material = bpy.data.materials.get(state["material"])  # undo reloads data: old references die
    undone = inventory()
    checks["one undo step removes it all"] = {
        "ok": undone[:3] == state["before"][:3] and material is not None and "stochtex texture" not in material.node_tree.nodes,
        "detail": "before %s, made %s, after undo %s" % (state["before"], made, undone)}
    s.write_report(args.out, "modal.json", checks)
    bpy.ops.wm.quit_blender()
    return None


bpy.app.timers.register(start_cancelled_bake, first_interval=1.0)
