"""The panel, in two places: the Shader Editor's sidebar (tab "stochtex") and Material properties."""

import textwrap

import bpy

from . import stex_cli
from .properties import has_osl, registry


def draw_analysis_options(box, settings):
    """The options field, checked as it is typed, under a disclosure that lists the chosen
    model's options (from the core's registry: the panel knows none of them itself)."""
    try:
        options = stex_cli.analysis_options(registry(bpy.context), settings.model)
    except stex_cli.StexError:
        return  # the model menu says "(stex not found)"
    if not options and not settings.analysis_options:
        return
    box.prop(settings, "show_analysis_options", emboss=False,
             icon="TRIA_DOWN" if settings.show_analysis_options else "TRIA_RIGHT")
    if settings.show_analysis_options:
        column = box.column(align=True)
        row = column.split(factor=0.5)
        row.label(text="option")
        row.label(text="default · range")
        models = list(dict.fromkeys(option["model"] for option in options))
        for model in models:
            if len(models) > 1:
                column.label(text=model.capitalize() + ":")
            for option in (o for o in options if o["model"] == model):
                key, summary = stex_cli.describe_option(option)
                row = column.split(factor=0.5)
                row.label(text=key)
                row.label(text=summary)
    box.prop(settings, "analysis_options", text="")
    try:
        stex_cli.option_args(settings.analysis_options, options)
    except stex_cli.StexError as error:
        # Wrapped: the sidebar elides a long label's middle, and this one is the fix's instructions.
        for k, line in enumerate(textwrap.wrap(str(error), 26)):
            box.label(text=line, icon="ERROR" if k == 0 else "BLANK1")


def draw_settings(layout, mat):
    settings = mat.stochtex
    box = layout.box()
    box.label(text="1. Analyse a photo", icon="IMAGE_DATA")
    box.template_ID(settings, "image", open="image.open")
    row = box.row()
    row.prop(settings, "model", text="")
    row.prop(settings, "histogram", text="")
    draw_analysis_options(box, settings)
    box.prop(settings, "unit_size")
    box.operator("stochtex.analyze", icon="SHADING_TEXTURE")
    if settings.chosen_model:
        box.label(text="Analysed as: " + settings.chosen_model, icon="CHECKMARK")

    box = layout.box()
    box.label(text="2. Render", icon="MATERIAL")
    box.prop(settings, "route", text="")
    if not has_osl():
        box.label(text="No OSL in this build", icon="INFO")
    if settings.route != "SOLID":
        box.prop(settings, "coordinates", text="")
        if settings.coordinates != "OBJECT":
            box.prop(settings, "uv_repeats")
    if settings.route == "OSL":
        box.prop(settings, "solid")
    else:
        box.prop(settings, "bake_size")
    if settings.route == "LIVE":
        box.prop(settings, "live_size")
        box.label(text="Cycles renders the .stex; EEVEE the baked map", icon="INFO")

    box = layout.box()
    box.label(text="3. Tweak", icon="MODIFIER")
    box.prop(settings, "stex_text", text="")
    if settings.stex_text is None:
        box.label(text="Analyse a photo first")
        return
    try:
        bands = stex_cli.band_count(stex_cli.parse_stex(settings.stex_text.as_string(), settings.stex_text.name))
    except stex_cli.StexError as error:
        box.label(text=str(error), icon="ERROR")
        return
    box.prop(settings, "seed")
    box.prop(settings, "use_histograms")
    column = box.column(align=True)
    column.label(text="Band gains (0 = finest grain)")
    for j in range(min(bands, len(settings.band_gains))):
        column.prop(settings, "band_gains", index=j, text="band %d" % j)
    box.label(text="Morph to")
    box.prop(settings, "morph_text", text="")
    if settings.morph_text is not None:
        box.prop(settings, "morph_t", slider=True)
    box.operator("stochtex.rebuild", icon="FILE_REFRESH")


class STOCHTEX_PT_node_editor(bpy.types.Panel):
    bl_label = "stochtex"
    bl_space_type = "NODE_EDITOR"
    bl_region_type = "UI"
    bl_category = "stochtex"

    @classmethod
    def poll(cls, context):
        space = context.space_data
        return space is not None and space.tree_type == "ShaderNodeTree" and context.material is not None

    def draw(self, context):
        draw_settings(self.layout, context.material)


class STOCHTEX_PT_material(bpy.types.Panel):
    bl_label = "stochtex"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    bl_options = {"DEFAULT_CLOSED"}

    @classmethod
    def poll(cls, context):
        return context.material is not None

    def draw(self, context):
        draw_settings(self.layout, context.material)


classes = [STOCHTEX_PT_node_editor, STOCHTEX_PT_material]
