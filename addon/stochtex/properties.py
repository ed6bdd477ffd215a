"""What the panel edits, stored on each material (material.stochtex) and saved with the blend."""

import bpy
from bpy.props import (BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty, IntProperty,
                       PointerProperty, StringProperty)

MAX_BANDS = 16  # gains shown for the finest 16 bands (a 2^17-pixel photo would have more)


def has_osl():
    """Official builds have OSL (Cycles, CPU); Debian's Blender 3.4 has not."""
    return bool(getattr(bpy.app.build_options, "cycles_osl", False))


_BAKED = ("BAKED", "Baked map", "The core bakes a tiled, MIP-mapped EXR; an Image Texture node reads it "
          "(Cycles and EEVEE, CPU and GPU)", 0)
_SOLID = ("SOLID", "Solid map", "The solid (3D) texture baked onto the active object's UV map: continuous "
          "across sharp edges and UV seams (Cycles and EEVEE, CPU and GPU; one map per object)", 1)
_LIVE = ("LIVE", "Live .stex", "Cycles reads the procedural texture itself through the stochtex OIIO plugin, at any "
         "resolution, no bake (Blender 5.2+ streams only the tiles a view needs); EEVEE and the viewport show a "
         "baked map of Bake size", 3)
_OSL = ("OSL", "OSL shader", "The texture evaluated per shading point by a generated OSL shader "
        "(Cycles CPU with Open Shading Language on)", 2)
# Blender keeps only pointers to a dynamic enum's strings: the lists must outlive the callback.
# A blend stores a dynamic enum's number, not its name: each route keeps its number for good.
_ROUTES_WITHOUT_OSL = [_BAKED, _SOLID, _LIVE]
_ROUTES_WITH_OSL = [_BAKED, _SOLID, _LIVE, _OSL]


# The models come from the core's registry (`stex models --json`), asked once per session.
_registry_cache = []
_models_cache = []


def registry(context):
    """The core's model registry (stex_cli.list_models), cached; raises StexError without stex."""
    if not _registry_cache:
        from . import stex_cli
        try:
            prefs = context.preferences.addons[__package__].preferences if context else None
        except (KeyError, AttributeError):
            prefs = None
        _registry_cache.extend(stex_cli.list_models(stex_cli.find_stex(getattr(prefs, "stex_path", ""))))
    return _registry_cache


def _models(self, context):
    if not _models_cache:
        from . import stex_cli
        try:
            _models_cache.extend(stex_cli.analysable_models(registry(context)))
        except stex_cli.StexError as error:
            return [("NONE", "(stex not found)", str(error))]
    return _models_cache


def texture_cache_streams(scene):
    """Cycles 5.2+ with its texture cache on reads a tiled, MIP-mapped file tile by tile."""
    return bpy.app.version >= (5, 2, 0) and bool(getattr(scene.render, "use_texture_cache", False))


def _routes(self, context):
    return _ROUTES_WITH_OSL if has_osl() else _ROUTES_WITHOUT_OSL


class StochtexPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    stex_path: StringProperty(name="stex executable", subtype="FILE_PATH",
                              description="Path of the stex tool; empty: $STOCHTEX_STEX, then PATH")

    plugin_path: StringProperty(name="OIIO plugin folder", subtype="DIR_PATH",
                                description="Folder holding stex.imageio.so built against this Blender's "
                                            "OpenImageIO, for the Live route; empty: $STOCHTEX_PLUGIN_PATH, then "
                                            "beside the stex tool")

    def draw(self, context):
        self.layout.prop(self, "stex_path")
        self.layout.prop(self, "plugin_path")


class StochtexSettings(bpy.types.PropertyGroup):
    # Analysis
    image: PointerProperty(type=bpy.types.Image, name="Photo",
                           description="The photo to analyse (empty: the active Image Texture node's image)")
    model: EnumProperty(name="Model", items=_models,
                        description="The texture model: Auto (the analysis chooses, the CLI's default) or one of "
                                    "the core's registry")
    chosen_model: StringProperty(name="Analysed as", default="",
                                 description="The model the last analysis used (with Auto: the one it chose)")
    histogram: EnumProperty(name="Histogram", default="auto", items=[
        ("auto", "Auto", "Match each channel's histogram where it measurably helps"),
        ("on", "On", "Always match the photo's histograms"),
        ("off", "Off", "Gaussian channels")])
    analysis_options: StringProperty(
        name="Options", default="",
        description="The model's analysis options as key=value pairs, e.g. filter-taps=1 (tiling: faster, "
                    "less accurate filtering) or J=80 (lrp); empty: the defaults. The list above the field shows "
                    "each with its default and range (docs/blender.md)")
    show_analysis_options: BoolProperty(name="Analysis options (key=value)", default=False,
                                        description="List the chosen model's analysis options, each with its "
                                                    "range and default")
    unit_size: FloatProperty(name="Photo width", default=1.0, min=1e-4, unit="LENGTH",
                             description="Physical width of the photo: the texture's scale on objects")
    # The result
    stex_text: PointerProperty(type=bpy.types.Text, name="Texture",
                               description="The analysed .stex, stored in the blend as a text block")
    # Tweaks (applied to a copy; the analysis stays as it was)
    seed: IntProperty(name="Seed", default=1, min=0, description="Another instance with the same statistics")
    band_gains: FloatVectorProperty(name="Band gains", size=MAX_BANDS, default=[1.0] * MAX_BANDS, min=0.0, max=4.0,
                                    description="Multiplies each band's weights; band 0 is the finest grain")
    use_histograms: BoolProperty(name="Histograms", default=True,
                                 description="Off: every channel Gaussian (softer, no long tails)")
    morph_text: PointerProperty(type=bpy.types.Text, name="Morph to",
                                description="Another analysed texture (.stex text) of the same model")
    morph_t: FloatProperty(name="Morph", default=0.0, min=0.0, max=1.0, subtype="FACTOR")
    # Rendering
    route: EnumProperty(name="Route", items=_routes)
    coordinates: EnumProperty(name="Coordinates", default="UV", items=[
        ("UV", "UV", "The active UV map; Repeats periods per UV unit"),
        ("OBJECT", "Object", "Object space, metres: the texture keeps its physical size"),
        ("GENERATED", "Generated", "The object's bounding box, 0 to 1")])
    solid: BoolProperty(name="Solid", default=False,
                        description="OSL route: the solid (3D) texture, continuous across sharp edges")
    uv_repeats: FloatProperty(name="Repeats", default=1.0, min=1e-3, description="Baked periods per UV unit")
    bake_size: IntProperty(name="Bake size", default=1024, min=64, max=16384,
                           description="Texels per side of the baked map (one seamless period); the Live "
                                       "route's map for EEVEE and the viewport, and its texel density")
    live_size: IntProperty(name="Live size", default=0, min=0, max=32768,
                           description="Live route: level-0 texels per side of the .stex Cycles reads (one "
                                       "seamless period, at Bake size's texel density). 0: 32768 where Cycles "
                                       "streams tiles (5.2+), 4096 where it reads the whole image (before 5.2)")


classes = [StochtexPreferences, StochtexSettings]


def register():
    bpy.types.Material.stochtex = PointerProperty(type=StochtexSettings)


def unregister():
    del bpy.types.Material.stochtex
