"""stochtex for Blender: a photo of a stochastic texture becomes a small procedural texture.

Panel: Shader Editor sidebar (tab "stochtex") and Material properties. See docs/blender.md.
"""

bl_info = {
    "name": "stochtex",
    "author": "stochtex developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Shader Editor > Sidebar > stochtex; Properties > Material > stochtex",
    "description": "Procedural textures by example: analyse a photo, bake or shade the texture",
    "doc_url": "https://example.invalid/stochtex/docs/blender.md",
    "category": "Material",
}

if "bpy" in locals():
    import importlib
    for _module in (stex_cli, properties, material, operators, ui):  # noqa: F821 (reload)
        importlib.reload(_module)

import bpy  # noqa: E402

from . import stex_cli, properties, material, operators, ui  # noqa: E402,F401

_classes = properties.classes + operators.classes + ui.classes


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    properties.register()
    # A blend opened with a live material renders at once: OIIO finds the plugin when Cycles
    # first meets the .stex. Without a plugin only the Live route needs one, and says so.
    try:
        operators.use_plugin(bpy.context)
    except stex_cli.StexError:
        pass


def unregister():
    properties.unregister()
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
