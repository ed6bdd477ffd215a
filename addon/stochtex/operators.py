"""Operators: analyse a photo, apply the tweaks and rebuild. Both run `stex` as background jobs.

Invoked from the UI they are modal: a timer polls the job, the window-manager progress bar and the
header show its progress, Esc cancels (the job is killed, its temporary folder removed). From
scripts and background mode (execute) they wait for the job. Data-blocks are created only in the
last step, after every job succeeded, so a failure or a cancel leaves nothing half-built, and the
whole result is one undo step.
"""

import os
import shutil

import bpy

from . import material, properties, stex_cli
from .properties import has_osl, registry


def _preferences(context):
    addon = context.preferences.addons.get(__package__)
    return addon.preferences if addon else None


def _executable(context):
    preferences = _preferences(context)
    return stex_cli.find_stex(preferences.stex_path if preferences else "")


def _target_material(context):
    """The material the panel shows; a new one on the active object if it has none."""
    mat = getattr(context, "material", None)
    if mat is None:
        obj = context.active_object
        if obj is not None and obj.active_material is not None:
            mat = obj.active_material
    return mat


def _photo_path(image, work):
    """A file stex can read for `image`: its file, or its packed bytes written to `work`."""
    if image is None:
        raise stex_cli.StexError("choose a photo first (or make an Image Texture node with an image active)")
    if image.packed_file is not None:
        extension = os.path.splitext(image.filepath)[1] or ".png"
        path = work.file("photo" + extension)
        with open(path, "wb") as out:
            out.write(image.packed_file.data)
        return path
    if not image.filepath:
        raise stex_cli.StexError("image '%s' has no file (generated or rendered): save it first" % image.name)
    path = bpy.path.abspath(image.filepath, library=image.library)
    if not os.path.isfile(path):
        raise stex_cli.StexError("image '%s': file not found: %s" % (image.name, path))
    return path


def _active_image_node_image(mat):
    if mat is None or not material.uses_nodes(mat):
        return None
    node = mat.node_tree.nodes.active
    return node.image if node is not None and node.type == "TEX_IMAGE" else None


def _texture_name(text_name):
    return os.path.splitext(text_name)[0]


def _store_text(name, content, existing=None):
    text = existing if existing is not None else bpy.data.texts.new(name)
    text.clear()
    text.write(content)
    return text


def _store_image(name, exr_path):
    """The baked map as an image data-block: a sidecar file beside a saved blend, else packed."""
    if bpy.data.filepath:
        folder = bpy.path.abspath("//stochtex")
        os.makedirs(folder, exist_ok=True)
        target = os.path.join(folder, name + ".exr")
        shutil.copyfile(exr_path, target)
        image = bpy.data.images.load(target, check_existing=False)
        image.filepath = "//stochtex/" + name + ".exr"
    else:
        image = bpy.data.images.load(exr_path, check_existing=False)
        image.pack()
    material.set_linear(image)
    return image


class _StexPipeline:
    """Mixin: runs the steps of plan() one after the other. A step is (label, stex arguments) or
    (label, a Python callable) for the quick work between two stex runs; a callable may return
    stex arguments computed from what the earlier steps wrote."""

    _timer = None

    def plan(self, context):
        raise NotImplementedError

    def finish(self, context):
        raise NotImplementedError

    def _start(self, context):
        self.work = stex_cli.WorkDir()
        self.executable = _executable(context)
        self.steps = self.plan(context)
        self.step = 0

    def _fail(self, message, level="ERROR"):
        if getattr(self, "work", None) is not None:
            self.work.remove()
        self.report({level}, message)
        return {"CANCELLED"}

    def execute(self, context):
        try:
            self._start(context)
            for label, step in self.steps:
                args = step() if callable(step) else step
                if args is not None:
                    stex_cli.run(self.executable, args)
            self.finish(context)
        except (stex_cli.StexError, OSError) as error:
            return self._fail(str(error))
        self.work.remove()
        return {"FINISHED"}

    def invoke(self, context, event):
        try:
            self._start(context)
            self._next_job()
        except (stex_cli.StexError, OSError) as error:
            return self._fail(str(error))
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.progress_begin(0, 100)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def _next_job(self):
        """Starts the job of step self.step, running Python steps on the way; False when done."""
        while self.step < len(self.steps):
            step = self.steps[self.step][1]
            args = step() if callable(step) else step
            if args is not None:
                self.job = stex_cli.StexJob(self.executable, args)
                return True
            self.step += 1
        return False

    def _end_modal(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)

    def modal(self, context, event):
        if event.type == "ESC":
            self.job.cancel()
            self._end_modal(context)
            return self._fail("stochtex: cancelled; nothing was changed", "WARNING")
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        try:
            done = self.job.poll()
            if done is None:
                fraction = (self.step + self.job.fraction) / len(self.steps)
                context.window_manager.progress_update(int(100 * fraction))
                context.workspace.status_text_set("stochtex: %s %d%% (Esc to cancel)"
                                                  % (self.steps[self.step][0], 100 * fraction))
                return {"RUNNING_MODAL"}
            self.step += 1
            if self._next_job():
                return {"RUNNING_MODAL"}
            self._end_modal(context)
            self.finish(context)
        except (stex_cli.StexError, OSError) as error:
            self._end_modal(context)
            return self._fail(str(error))
        self.work.remove()
        return {"FINISHED"}


def use_plugin(context):
    """Puts the stochtex OIIO plugin's folder (stex_cli.find_plugin) on OIIO's search path in this
    process, so that Cycles reads a live .stex; raises StexError where there is none."""
    preferences = _preferences(context)
    try:
        executable = _executable(context)
    except stex_cli.StexError:
        executable = ""  # the plugin can still be named by the preference or the environment
    stex_cli.add_plugin_path(stex_cli.find_plugin(preferences.plugin_path if preferences else "", executable))


def _render_steps(self, settings, stex_path, name):
    """The stex runs that turn a .stex file into what the chosen route needs."""
    if settings.route == "OSL":
        if not has_osl():
            raise stex_cli.StexError("this Blender has no OSL (e.g. Debian's build): use the baked route")
        return [("OSL shader", stex_cli.osl_args(stex_path, self.work.file(name + ".osl")))]
    if settings.route == "SOLID":
        obj = bpy.context.active_object
        if obj is None or obj.type != "MESH" or not obj.data.uv_layers:
            raise stex_cli.StexError("a solid map needs an active mesh object with a UV map (UV > Smart UV Project)")
        positions = self.work.file("positions.exr")

        def solid_bake():
            # Object coordinates are metres; the texture's unit is unit_size_m metres (from the
            # .stex, which exists only once the analysis has run).
            with open(stex_path) as source:
                unit_size_m = float(stex_cli.parse_stex(source.read(), name)["scale"]["unit_size_m"])
            return stex_cli.solid_bake_args(stex_path, self.work.file(name + ".exr"), positions, 1.0 / unit_size_m)
        return [("surface positions", lambda: material.bake_positions(bpy.context, obj, self.mat, settings.bake_size,
                                                                      positions)),
                ("solid bake", solid_bake)]
    if settings.route == "LIVE":
        use_plugin(bpy.context)  # before any work: without the plugin Cycles cannot read the live file
    return [("bake", stex_cli.bake_args(stex_path, self.work.file(name + ".exr"), settings.bake_size))]


def _store_live(name, stex_text_content, size):
    """The live file: the .stex with a size² image block, beside a saved blend (as the baked maps
    are) or in Blender's temporary folder, replaced atomically, and its image data-block (reloaded
    so that Cycles reads the new texture after a tweak). Returns the image and whether the file
    lives only as long as this session."""
    folder = bpy.path.abspath("//stochtex") if bpy.data.filepath else os.path.join(bpy.app.tempdir, "stochtex")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, name + ".stex")
    stex_cli.write_atomically(path, stex_cli.live_stex(stex_text_content, size, name))
    image = bpy.data.images.get(name + ".stex")
    if image is None or bpy.path.abspath(image.filepath) != path:
        # Blender's own reader logs "unknown file-format": it knows no OIIO plugins (docs/blender.md).
        image = bpy.data.images.load(path, check_existing=False)
        image.name = name + ".stex"
        if bpy.data.filepath:
            image.filepath = "//stochtex/" + name + ".stex"
    else:
        image.reload()
    material.set_linear(image)  # the plugin's texels are linear Rec.709, as the baked maps' are
    return image, not bpy.data.filepath


def _finish_render(self, context, mat, settings, name, stex_text_content):
    data = stex_cli.parse_stex(stex_text_content, name)
    unit_size_m = float(data["scale"]["unit_size_m"])
    if settings.route == "OSL":
        # The shader names the images it reads (noise tiles, tables, moment maps) by absolute
        # path: keep them beside the blend (or in a folder that outlives this operation).
        folder = bpy.path.abspath("//stochtex") if bpy.data.filepath else os.path.join(
            bpy.app.tempdir or self.work.path, "stochtex")
        os.makedirs(folder, exist_ok=True)
        with open(self.work.file(name + ".osl")) as source:
            shader = source.read()
        for image in stex_cli.shader_images(shader):
            shutil.copyfile(image, os.path.join(folder, os.path.basename(image)))
        shader = shader.replace(self.work.path, folder)
        osl_text = _store_text(name + ".osl", shader, bpy.data.texts.get(name + ".osl"))
        context.scene.cycles.shading_system = True
        material.build_material(mat, settings, name, osl_text=osl_text, unit_size_m=unit_size_m)
        return
    exr = self.work.file(name + ".exr")
    if settings.route == "SOLID":
        name = name + "." + bpy.path.clean_name(context.active_object.name)  # one map per object
    old = bpy.data.images.get(name + ".exr")
    image = _store_image(name, exr)
    period = material.map_period(settings, settings.bake_size, stex_cli.period_units(data, settings.bake_size),
                                 unit_size_m, settings.bake_size)
    live = None
    if settings.route == "LIVE":
        size = stex_cli.live_size(settings.live_size, properties.texture_cache_streams(context.scene))
        live_image, temporary = _store_live(name, stex_text_content, size)
        live_units = stex_cli.period_units(data, size, stex_cli.image_scale(data))
        live = (live_image, material.map_period(settings, size * stex_cli.image_scale(data), live_units, unit_size_m,
                                                settings.bake_size))
        if temporary:
            self.report({"WARNING"}, "stochtex: the live file is in Blender's temporary folder until the blend is "
                                     "saved; save it, then Apply Tweaks, to keep it beside the blend")
    material.build_material(mat, settings, name, image=image, period=period, live=live)
    if old is not None and old.users == 0:
        bpy.data.images.remove(old)
    image.name = name + ".exr"


class STOCHTEX_OT_analyze(_StexPipeline, bpy.types.Operator):
    """Analyse the photo into a procedural texture, store it in the blend and build the material"""

    bl_idname = "stochtex.analyze"
    bl_label = "Analyse Photo"
    bl_options = {"REGISTER", "UNDO"}

    filepath: bpy.props.StringProperty(name="Photo file", subtype="FILE_PATH",
                                       description="Analyse this file instead of the panel's image")

    @classmethod
    def poll(cls, context):
        return _target_material(context) is not None

    def plan(self, context):
        self.mat = _target_material(context)
        settings = self.mat.stochtex
        if self.filepath:
            photo = bpy.path.abspath(self.filepath)
            if not os.path.isfile(photo):
                raise stex_cli.StexError("photo not found: %s" % photo)
        else:
            photo = _photo_path(settings.image or _active_image_node_image(self.mat), self.work)
        self.texture_name = bpy.path.clean_name(os.path.splitext(os.path.basename(photo))[0]) or "texture"
        self.stex_path = self.work.file(self.texture_name + ".stex")
        model = None if settings.model == "NONE" else settings.model
        options = stex_cli.option_args(settings.analysis_options, stex_cli.analysis_options(registry(context), model or "auto"))
        analysis = stex_cli.analyze_args(photo, self.stex_path, model, settings.histogram, settings.seed,
                                         settings.unit_size, options)
        return [("analysis", analysis)] + _render_steps(self, settings, self.stex_path, self.texture_name)

    def finish(self, context):
        settings = self.mat.stochtex
        with open(self.stex_path) as source:
            content = source.read()
        existing = bpy.data.texts.get(self.texture_name + ".stex")
        settings.stex_text = _store_text(self.texture_name + ".stex", content, existing)
        settings.band_gains = [1.0] * len(settings.band_gains)
        settings.use_histograms = True
        _finish_render(self, context, self.mat, settings, self.texture_name, content)
        data = stex_cli.parse_stex(content)
        model, scores = stex_cli.model_choice(data)
        settings.chosen_model = model
        chosen = "%s (auto: %s)" % (model, ", ".join("%s %.2f" % item for item in scores.items())) if scores else model
        self.report({"INFO"}, "stochtex: %s analysed as %s (%d bands) into %s" % (
            self.texture_name, chosen, stex_cli.band_count(data), self.mat.name))


class STOCHTEX_OT_rebuild(_StexPipeline, bpy.types.Operator):
    """Apply seed, band gains, histograms and morph to the stored texture and re-bake or re-shade"""

    bl_idname = "stochtex.rebuild"
    bl_label = "Apply Tweaks"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        mat = _target_material(context)
        return mat is not None and mat.stochtex.stex_text is not None

    def plan(self, context):
        self.mat = _target_material(context)
        settings = self.mat.stochtex
        self.texture_name = _texture_name(settings.stex_text.name)
        source = self.work.file("analysed.stex")
        _write(source, settings.stex_text.as_string())
        self.tweaked = self.work.file(self.texture_name + ".stex")
        steps = []
        if settings.morph_text is not None and settings.morph_t > 0:
            other = self.work.file("other.stex")
            _write(other, settings.morph_text.as_string())
            morphed = self.work.file("morphed.stex")
            steps.append(("morph", stex_cli.morph_args(source, other, settings.morph_t, morphed)))
            source = morphed
        steps.append(("tweaks", lambda: self._tweak(source, settings)))
        return steps + _render_steps(self, settings, self.tweaked, self.texture_name)

    def _tweak(self, source_path, settings):
        with open(source_path) as source:
            text = source.read()
        gains = list(settings.band_gains)[:stex_cli.band_count(stex_cli.parse_stex(text, self.texture_name))]
        _write(self.tweaked, stex_cli.apply_tweaks(text, settings.seed, gains, settings.use_histograms, self.texture_name))

    def finish(self, context):
        settings = self.mat.stochtex
        with open(self.tweaked) as source:
            content = source.read()
        _finish_render(self, context, self.mat, settings, self.texture_name, content)
        self.report({"INFO"}, "stochtex: %s rebuilt (seed %d)" % (self.texture_name, settings.seed))


def _write(path, text):
    with open(path, "w") as out:
        out.write(text)


classes = [STOCHTEX_OT_analyze, STOCHTEX_OT_rebuild]
