"""The add-on's only way to the stochtex core: the `stex` command-line tool, run as a subprocess.

Pure Python (no bpy, no numpy): tests/addon/ runs it with the system Python.

Why the CLI and not a C API loaded with ctypes (docs/blender.md): the core links OpenImageIO,
OpenEXR and OpenColorIO, and Blender links its own copies of the same libraries (official builds
bundle other versions than the system's); loading both into Blender's process invites symbol
clashes that crash Blender. A subprocess keeps them apart, runs big bakes on all cores without
holding Python's GIL, can be cancelled at any moment by killing it, and a crash in it is an
error message, not a lost scene. The CLI's option names are already a stable public interface
(cli/commands.h); `stex --progress-lines` gives machine-readable progress.
"""

import glob
import json
import re
import os
import shutil
import subprocess
import tempfile
import threading


class StexError(Exception):
    """A problem to show the user as it is: it names the file or option at fault."""


def find_stex(preference=""):
    """The stex executable: the add-on preference, $STOCHTEX_STEX, then PATH."""
    for candidate in (preference, os.environ.get("STOCHTEX_STEX", "")):
        if candidate:
            path = os.path.abspath(os.path.expanduser(candidate))
            if os.path.isfile(path) and os.access(path, os.X_OK):
                return path
            raise StexError("stex executable not found at '%s' (add-on preferences or $STOCHTEX_STEX)" % candidate)
    found = shutil.which("stex")
    if not found:
        raise StexError("the stex tool is not installed: put it on PATH, set $STOCHTEX_STEX, "
                        "or set its path in the add-on preferences")
    return found


def analyze_args(photo, output, model=None, histogram="auto", seed=1, unit_size_m=1.0, options=()):
    """model None: the core's default model; options: more CLI arguments (option_args)."""
    args = ["analyze", photo, "-o", output] + (["--model", model] if model else [])
    return args + ["--histogram", histogram, "--seed", str(int(seed)), "--unit-size", repr(float(unit_size_m))] + list(options)


def analysis_options(models, model):
    """The registry's analysis options (dicts: key, type, range, default, unit, doc, and "model",
    the model's name) that analysing as `model` takes: that model's, or with "auto" those of
    every model that analyses photos (the CLI passes each to its model)."""
    return [dict(option, model=m["name"]) for m in models
            if m.get("capabilities", {}).get("analysis") and model in ("auto", m["name"])
            for option in m.get("analysis_options", [])]


def describe_option(option):
    """The panel's two columns for an option: its key and "2 · [1, 4] taps per axis", its
    default then its range (first the default: a narrow sidebar elides a line's end)."""
    kind = " ".join(part for part in (option.get("range", ""), option.get("unit", "")) if part)
    return option["key"], " · ".join(part for part in (option.get("default", ""), kind) if part)


def option_args(text, options):
    """The CLI arguments for the panel's analysis options: "key=value" pairs separated by spaces
    or commas ("filter-taps=1, J=80"; a leading "--" is allowed). A key none of `options`
    (analysis_options) has, a pair without "=" or a key given twice is an error naming it; the
    values are the CLI's to check (its message names the option and its range)."""
    known = {option["key"]: option for option in options}
    args, seen = [], set()
    for pair in text.replace(",", " ").split():
        key, equals, value = pair.partition("=")
        key = key[2:] if key.startswith("--") else key
        if not equals or not key or not value:
            example = known.get(key) or next(iter(known.values()), {"key": "key", "default": "value"})
            raise StexError("analysis option '%s': write it as key=value (e.g. %s=%s)" % (
                pair, example["key"], example["default"] or "1"))
        if key not in known:
            valid = ", ".join(sorted(known)) or "none"
            raise StexError("analysis option '%s': not an option of this model (its options: %s)" % (key, valid))
        if key in seen:
            raise StexError("analysis option '%s' is given twice" % key)
        seen.add(key)
        args += ["--" + key, value]
    return args


def list_models(executable):
    """The core's model registry (`stex models --json`): a list of dicts with name, summary, doc,
    capabilities, parameters and analysis_options, in the core's order."""
    text = run(executable, ["models", "--json"])
    try:
        return json.loads(text)["models"]
    except (ValueError, KeyError, TypeError) as error:
        raise StexError("%s models --json: unexpected output (%s)" % (executable, error)) from None


AUTO_MODEL = ("auto", "Auto", "Fit every model, score each against the photo and keep the closest "
              "(of those within 10 %, the smallest file); the panel then shows the choice")


def analysable_models(models):
    """(identifier, name, description) for each model that analyses photos, after "Auto" (the
    analysis chooses; the CLI's default): the panel's choices."""
    return [AUTO_MODEL] + [(m["name"], m["name"].capitalize(), "%s (%s)" % (m["summary"], m["doc"]))
                           for m in models if m.get("capabilities", {}).get("analysis")]


def _candidate(model, colour):
    return model if colour == "pca" else "%s/%s" % (model, colour)


def model_choice(data):
    """The candidate a parsed .stex is ("tiling", or "tiling/rgb" when fitted in another colour
    mode than pca) and, when the analysis chose it, every candidate's penalty (candidate ->
    penalty, lower is closer to the photo); {} when a model was named."""
    scores = data.get("provenance", {}).get("model_choice", [])
    chosen = _candidate(data.get("model", ""), data.get("colour", {}).get("mode", "pca"))
    return chosen, {_candidate(s["model"], s["colour"]): s["penalty"] for s in scores}


def bake_args(texture, output, size, half=True):
    args = ["bake", texture, "-o", output, "--size", str(int(size))]
    return args + (["--half"] if half else [])


def solid_bake_args(texture, output, positions, units_per_position):
    return ["bake", texture, "-o", output, "--positions", positions, "--position-scale", repr(float(units_per_position))]


def osl_args(texture, output):
    return ["osl", texture, "-o", output]


def shader_images(shader_text):
    """The image files a shader written by `stex osl` reads (its string parameters ending in .exr)."""
    return re.findall(r'^    string \w+ = "([^"]+\.exr)",$', shader_text, re.MULTILINE)


def morph_args(a, b, t, output):
    return ["morph", a, b, "--t", repr(float(t)), "-o", output]


class StexJob:
    """One `stex` run in the background. poll() never blocks: the UI keeps running.

    Progress comes from the "progress FRACTION STAGE" lines of `stex --progress-lines`; the
    error message is stex's own "stex: error: ..." line.
    """

    def __init__(self, executable, args):
        self.command = [executable, "--progress-lines"] + list(args)
        self.fraction = 0.0
        self.stage = "starting"
        self._stderr = []
        # Below the UI's priority: a bake uses every core, and Blender must keep drawing.
        lower_priority = (lambda: os.nice(10)) if hasattr(os, "nice") else None
        try:
            self._process = subprocess.Popen(self.command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                             stdin=subprocess.DEVNULL, text=True, preexec_fn=lower_priority)
        except OSError as error:
            raise StexError("cannot run %s: %s" % (executable, error.strerror)) from None
        self._stdout = ""
        self._reader = threading.Thread(target=self._read_stderr, daemon=True)
        self._reader.start()

    def _read_stderr(self):
        for line in self._process.stderr:
            parts = line.split()
            if len(parts) >= 2 and parts[0] == "progress":
                try:
                    self.fraction = float(parts[1])
                    self.stage = " ".join(parts[2:]) or self.stage
                    continue
                except ValueError:
                    pass
            self._stderr.append(line.rstrip("\n"))

    def poll(self):
        """None while running; else the stdout text. Raises StexError if stex failed."""
        if self._process.poll() is None:
            return None
        return self._finish()

    def wait(self):
        self._process.wait()
        return self._finish()

    def _finish(self):
        self._stdout = self._process.stdout.read()
        self._reader.join()
        self._close_pipes()
        if self._process.returncode != 0:
            raise StexError(error_message(self._stderr, self._process.returncode))
        return self._stdout

    def cancel(self):
        if self._process.poll() is None:
            self._process.kill()
            self._process.wait()
        self._reader.join()
        self._close_pipes()

    def _close_pipes(self):
        # Closed here, not when the garbage collector finds them: Blender runs stex once per
        # step for a whole session, and each run would otherwise hold two descriptors open.
        for pipe in (self._process.stdout, self._process.stderr):
            if pipe is not None and not pipe.closed:
                pipe.close()


def error_message(stderr_lines, returncode):
    """stex's own message without the "stex: error: " prefix, else the last lines it printed."""
    for line in stderr_lines:
        if line.startswith("stex: error: "):
            return line[len("stex: error: "):]
    text = " ".join(line.strip() for line in stderr_lines[-3:] if line.strip())
    if returncode < 0:
        return "stex was killed by signal %d %s" % (-returncode, text)
    return text or ("stex failed with exit status %d" % returncode)


def run(executable, args):
    """Runs stex to completion (background mode, tests); returns stdout."""
    return StexJob(executable, args).wait()


# ---- The .stex text: reading and the artist's tweaks ---------------------------------------------

def parse_stex(text, name="texture"):
    try:
        data = json.loads(text)
    except ValueError as error:
        raise StexError("%s: not a .stex file (%s)" % (name, error)) from None
    if not isinstance(data, dict) or data.get("format") != "stex":
        raise StexError("%s: not a .stex file (no \"format\": \"stex\")" % name)
    return data


def band_count(data):
    weights = data.get("parameters", {}).get("band_weights")
    return len(weights[0]) if weights else 0


def apply_tweaks(text, seed=None, band_gains=None, histograms=True, name="texture"):
    """The .stex text with the panel's tweaks applied; the stored analysis is never changed.

    seed: another instance of the same texture; band_gains[j] multiplies every channel's weight
    of band j (0 removes a band: coarser or finer grain); histograms=False makes every channel
    Gaussian (the format's null map). `stex` validates the result when it reads it.
    """
    data = parse_stex(text, name)
    if seed is not None:
        data["seed"] = int(seed) & 0xFFFFFFFF
    if band_gains:
        weights = data.get("parameters", {}).get("band_weights")
        if weights is None:
            raise StexError("%s: band gains need a model with band weights (%s has none)" % (name, data.get("model")))
        for channel in weights:
            for j in range(min(len(channel), len(band_gains))):
                channel[j] = channel[j] * max(0.0, float(band_gains[j]))
    if not histograms:
        data["histograms"] = [None, None, None]
    return json.dumps(data, indent=2) + "\n"


def period_units(data, size, scale=1.0):
    """Texture units covered by a bake of `size` texels (stex bake: size · scale / ppu)."""
    return size * scale / float(data["scale"]["pixels_per_unit"])


class WorkDir:
    """A private temporary folder for one operation; removed on cancel or error."""

    def __init__(self):
        self.path = tempfile.mkdtemp(prefix="stochtex-blender-")

    def file(self, name):
        return os.path.join(self.path, name)

    def remove(self):
        shutil.rmtree(self.path, ignore_errors=True)


# ---- The live route: Cycles reads the .stex itself through the OIIO plugin ----------------------

PLUGIN_FILE = "stex.imageio.so"
# The largest square level 0 the format allows (width × height ≤ 2^30, docs/limits.md): a host that
# streams tiles (Cycles 5.2's texture cache) pays only for the tiles a view needs, so the period
# may as well be as long as possible.
LIVE_SIZE_STREAMED = 32768
# A host that reads level 0 whole (Blender before 5.2) holds it in memory: 4096² RGB floats are
# 192 MB, made in 1–2 s.
LIVE_SIZE_WHOLE = 4096


def live_size(setting, streams):
    """Level-0 texels per side of the live file: the panel's size, or for 0 the host's default
    (streams: Cycles reads only the tiles a view needs)."""
    if setting:
        return int(setting)
    return LIVE_SIZE_STREAMED if streams else LIVE_SIZE_WHOLE


def live_stex(text, size, name="texture"):
    """The .stex text with an image block declaring a size × size level 0 (its other keys, tile
    size and scale, kept): what the OIIO plugin presents to Cycles."""
    data = parse_stex(text, name)
    image = dict(data.get("image") or {})
    image["width"] = image["height"] = int(size)
    data["image"] = image
    return json.dumps(data, indent=2) + "\n"


def image_scale(data):
    """Photo pixels per level-0 texel of the plugin's image (the image block's scale, default 1)."""
    return float((data.get("image") or {}).get("scale", 1.0))


def find_plugin(preference="", stex_path=""):
    """The folder holding the stochtex OIIO plugin: the add-on preference, $STOCHTEX_PLUGIN_PATH,
    then beside the stex tool (an install's lib/, or a build tree's plugins/)."""
    for candidate in (preference, os.environ.get("STOCHTEX_PLUGIN_PATH", "")):
        if candidate:
            folder = os.path.abspath(os.path.expanduser(candidate))
            if os.path.isfile(os.path.join(folder, PLUGIN_FILE)):
                return folder
            raise StexError("the stochtex OIIO plugin (%s) is not in '%s' (add-on preferences or "
                            "$STOCHTEX_PLUGIN_PATH)" % (PLUGIN_FILE, candidate))
    if stex_path:
        prefix = os.path.dirname(os.path.dirname(os.path.realpath(stex_path)))
        for folder in [os.path.join(prefix, "lib")] + sorted(glob.glob(os.path.join(prefix, "lib", "*-linux-gnu"))) + \
                [os.path.join(prefix, "lib64"), os.path.join(prefix, "plugins")]:
            if os.path.isfile(os.path.join(folder, PLUGIN_FILE)):
                return folder
    raise StexError("the live route needs the stochtex OIIO plugin (%s) built against this Blender's "
                    "OpenImageIO: set its folder in the add-on preferences or $STOCHTEX_PLUGIN_PATH "
                    "(docs/blender.md, Live)" % PLUGIN_FILE)


def add_plugin_path(folder, environ=None):
    """Puts `folder` first on OIIO's plugin search path, under both names OIIO reads: OIIO 3.x's
    OPENIMAGEIO_PLUGIN_PATH and 2.x's OIIO_LIBRARY_PATH. OIIO reads them each time it looks
    for a reader it does not know yet, so setting them in Blender's process before Cycles
    first meets a .stex is enough."""
    environ = os.environ if environ is None else environ
    for variable in ("OPENIMAGEIO_PLUGIN_PATH", "OIIO_LIBRARY_PATH"):
        paths = [p for p in environ.get(variable, "").split(os.pathsep) if p]
        if folder not in paths:
            environ[variable] = os.pathsep.join([folder] + paths)


def write_atomically(path, text):
    """Writes `path` through a temporary file beside it: a reader (Cycles rendering while the
    artist applies a tweak) sees the old file or the new one, never half of one."""
    folder = os.path.dirname(path) or "."
    handle, temporary = tempfile.mkstemp(prefix=".stochtex-", dir=folder)
    try:
        with os.fdopen(handle, "w") as out:
            out.write(text)
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise
