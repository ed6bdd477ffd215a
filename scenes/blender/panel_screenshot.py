"""A screenshot of the add-on's panel (docs/images/blender-panel.png), from Blender's real UI.

Needs a display: run under Xvfb, e.g.
  xvfb-run -a -s "-screen 0 1400x900x24" blender --factory-startup --enable-event-simulate \\
      --python scenes/blender/panel_screenshot.py -- \\
      --addon build/addon/stochtex-0.1.0.zip --photo data/exemplars/concrete_512.png --out out/panel
The default cube gets the analysed texture; the 3D view becomes a Shader Editor whose sidebar
shows the stochtex tab. Blender 3.4 has no Python API for a sidebar's active tab, so the script
clicks it (simulated events: Esc closes the splash, then a click on the tab).
"""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stochtex_scene as s  # noqa: E402

args = s.arguments(__doc__)
os.makedirs(args.out, exist_ok=True)
s.install_addon(args.addon)
mat = s.default_cube_material()
mat.stochtex.bake_size = 512
mat.stochtex.image = bpy.data.images.load(os.path.abspath(args.photo))
assert bpy.ops.stochtex.analyze() == {"FINISHED"}


def arrange():
    window = bpy.context.window_manager.windows[0]
    areas = sorted(window.screen.areas, key=lambda a: a.width * a.height, reverse=True)
    editor = areas[0]
    editor.type = "NODE_EDITOR"
    editor.ui_type = "ShaderNodeTree"
    editor.spaces.active.show_region_ui = True
    for region in editor.regions:
        if region.type == "UI" and hasattr(region, "active_panel_category"):
            region.active_panel_category = "stochtex"
    bpy.app.timers.register(lambda: frame(window, editor), first_interval=1.0)
    return None


def frame(window, editor):
    main = next(r for r in editor.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=window, area=editor, region=main):
        bpy.ops.node.view_all()
    bpy.app.timers.register(lambda: click_tab(window, editor), first_interval=0.5)
    return None


def click_tab(window, editor):
    window.event_simulate(type="ESC", value="PRESS")
    window.event_simulate(type="ESC", value="RELEASE")
    sidebar = next(r for r in editor.regions if r.type == "UI")
    # The tabs run down the sidebar's right edge, one per category, ~(bottom-up) last = stochtex.
    x = sidebar.x + sidebar.width - 10
    for y in range(sidebar.y + sidebar.height - 30, sidebar.y, -8):
        window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
    window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=TAB_Y(sidebar))
    window.event_simulate(type="LEFTMOUSE", value="PRESS", x=x, y=TAB_Y(sidebar))
    window.event_simulate(type="LEFTMOUSE", value="RELEASE", x=x, y=TAB_Y(sidebar))
    bpy.app.timers.register(lambda: shoot(window), first_interval=1.5)
    return None


def TAB_Y(sidebar):
    # Tabs are ~50 px tall from the top (Node, Tool, View, Options, stochtex at 1x UI scale).
    return sidebar.y + sidebar.height - 4 * 52 - 60


def shoot(window):
    with bpy.context.temp_override(window=window):
        bpy.ops.screen.screenshot(filepath=os.path.join(os.path.abspath(args.out), "panel.png"))
    bpy.ops.wm.quit_blender()
    return None


bpy.app.timers.register(arrange, first_interval=1.0)
