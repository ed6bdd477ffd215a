"""Unit tests of the add-on's CLI layer (addon/stochtex/stex_cli.py), without Blender.

Run by CTest (AddonCliLayer) with the system Python: STOCHTEX_STEX names the built stex and
STOCHTEX_EXEMPLAR a photo. The module is loaded from its file: the add-on package's __init__
imports bpy, which only exists inside Blender.
"""

import importlib.util
import json
import os
import shutil
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "..", "addon", "stochtex", "stex_cli.py")
spec = importlib.util.spec_from_file_location("stex_cli", SOURCE)
stex_cli = importlib.util.module_from_spec(spec)
spec.loader.exec_module(stex_cli)

STEX = os.environ.get("STOCHTEX_STEX", "")
PHOTO = os.environ.get("STOCHTEX_EXEMPLAR", os.path.join(HERE, "..", "..", "data", "exemplars", "concrete_512.png"))


@unittest.skipUnless(STEX, "STOCHTEX_STEX not set (CTest sets it to the built stex)")
class StexCliTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="stochtex-addon-test-")
        cls.stex = stex_cli.find_stex()
        cls.texture = os.path.join(cls.dir, "t.stex")
        stex_cli.run(cls.stex, stex_cli.analyze_args(PHOTO, cls.texture, "wavelet", histogram="on", seed=3,
                                                     unit_size_m=0.5))
        with open(cls.texture) as f:
            cls.text = f.read()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_analysis_options_reach_the_file(self):
        data = stex_cli.parse_stex(self.text)
        self.assertEqual(data["seed"], 3)
        self.assertEqual(data["scale"]["unit_size_m"], 0.5)
        self.assertEqual(stex_cli.band_count(data), 8)
        self.assertTrue(all(h is not None for h in data["histograms"]))

    def test_models_come_from_the_core_registry(self):
        models = stex_cli.list_models(self.stex)
        names = [m["name"] for m in models]
        self.assertEqual(len(names), len(set(names)))
        choices = stex_cli.analysable_models(models)
        # "auto" (the CLI's default), then exactly the models whose capabilities say they analyse
        # photos, in the registry's order.
        analysable = [m["name"] for m in models if m["capabilities"]["analysis"]]
        self.assertEqual([c[0] for c in choices], ["auto"] + analysable)
        self.assertGreaterEqual(len(choices), 2)
        # The first is the CLI's default: analysing without --model chooses, and says how.
        chosen = os.path.join(self.dir, "chosen.stex")
        stex_cli.run(self.stex, stex_cli.analyze_args(PHOTO, chosen))
        with open(chosen) as f:
            model, scores = stex_cli.model_choice(json.load(f))
        # Every analysable model is a candidate (tiling also in rgb colour).
        self.assertEqual(sorted(set(s.split("/")[0] for s in scores)), sorted(analysable))
        self.assertIn(model, scores)
        # The rule: within 10 % of the lowest penalty.
        self.assertLessEqual(scores[model], 1.10 * min(scores.values()) + 1e-12)
        for model in models:
            self.assertTrue(model["parameters"], model["name"])

    def test_bake_reports_progress_and_writes_a_mip_mapped_exr(self):
        out = os.path.join(self.dir, "bake.exr")
        job = stex_cli.StexJob(self.stex, stex_cli.bake_args(self.texture, out, 512))
        while job.poll() is None:
            time.sleep(0.01)
        self.assertEqual(job.fraction, 1.0)
        self.assertEqual(job.stage, "bake")
        self.assertTrue(os.path.isfile(out))
        self.assertFalse(os.path.exists(out + ".tmp"))

    def test_analysis_options_come_from_the_registry_and_reach_the_file(self):
        models = stex_cli.list_models(self.stex)
        tiling = stex_cli.analysis_options(models, "tiling")
        self.assertIn("filter-taps", [o["key"] for o in tiling])
        self.assertTrue(all(o["model"] == "tiling" for o in tiling))
        self.assertNotIn("filter-taps", [o["key"] for o in stex_cli.analysis_options(models, "wavelet")])
        # Auto takes every analysing model's options (the CLI hands each to its model).
        every = [(o["model"], o["key"]) for o in stex_cli.analysis_options(models, "auto")]
        self.assertEqual(every, [(m["name"], o["key"]) for m in models if m["capabilities"]["analysis"]
                                 for o in m["analysis_options"]])
        key, summary = stex_cli.describe_option(next(o for o in tiling if o["key"] == "filter-taps"))
        self.assertEqual(key, "filter-taps")
        self.assertTrue(summary.startswith("2 · [1, 4] taps"), summary)
        out = os.path.join(self.dir, "one_tap.stex")
        stex_cli.run(self.stex, stex_cli.analyze_args(PHOTO, out, "tiling", options=stex_cli.option_args(
            "filter-taps=1, exemplar-size=64", tiling)))
        with open(out) as f:
            self.assertEqual(json.load(f)["parameters"]["filter_taps"], 1)
        # A value out of range is the CLI's to reject, naming the option and its range.
        with self.assertRaises(stex_cli.StexError) as caught:
            stex_cli.run(self.stex, stex_cli.analyze_args(PHOTO, out + ".bad", "tiling",
                                                          options=stex_cli.option_args("filter-taps=9", tiling)))
        self.assertIn("--filter-taps", str(caught.exception))
        self.assertIn("[1, 4]", str(caught.exception))
        self.assertFalse(os.path.exists(out + ".bad"))

    def test_errors_are_stex_messages(self):
        not_image = os.path.join(self.dir, "notes.png")
        with open(not_image, "w") as f:
            f.write("text")
        with self.assertRaises(stex_cli.StexError) as caught:
            stex_cli.run(self.stex, stex_cli.analyze_args(not_image, os.path.join(self.dir, "x.stex")))
        self.assertIn("notes.png", str(caught.exception))
        self.assertNotIn("stex: error:", str(caught.exception))
        self.assertFalse(os.path.exists(os.path.join(self.dir, "x.stex")))

    def test_cancel_kills_the_bake_and_leaves_no_map(self):
        out = os.path.join(self.dir, "big.exr")
        job = stex_cli.StexJob(self.stex, stex_cli.bake_args(self.texture, out, 8192))
        time.sleep(0.3)
        self.assertIsNone(job.poll())
        job.cancel()
        self.assertFalse(os.path.exists(out))

    def test_finished_failed_and_cancelled_jobs_leave_no_descriptor_open(self):
        def open_descriptors():
            return len(os.listdir("/proc/self/fd"))
        if not os.path.isdir("/proc/self/fd"):
            self.skipTest("no /proc/self/fd")
        before = open_descriptors()
        for _ in range(3):
            stex_cli.run(self.stex, ["info", self.texture])
            with self.assertRaises(stex_cli.StexError):
                stex_cli.run(self.stex, ["info", os.path.join(self.dir, "missing.stex")])
            job = stex_cli.StexJob(self.stex, stex_cli.bake_args(self.texture, os.path.join(self.dir, "big.exr"), 8192))
            job.cancel()
        self.assertEqual(open_descriptors(), before)

    def test_tweaks_give_a_valid_texture(self):
        tweaked = stex_cli.apply_tweaks(self.text, seed=9, band_gains=[0.0, 2.0], histograms=False)
        data = json.loads(tweaked)
        original = json.loads(self.text)
        self.assertEqual(data["seed"], 9)
        self.assertEqual(data["histograms"], [None, None, None])
        for c in range(3):
            self.assertEqual(data["parameters"]["band_weights"][c][0], 0.0)
            self.assertAlmostEqual(data["parameters"]["band_weights"][c][1], 2 * original["parameters"]["band_weights"][c][1])
            self.assertEqual(data["parameters"]["band_weights"][c][2:], original["parameters"]["band_weights"][c][2:])
        path = os.path.join(self.dir, "tweaked.stex")
        with open(path, "w") as f:
            f.write(tweaked)
        stex_cli.run(self.stex, ["info", path])  # stex's strict reader accepts it

    def test_morph_and_osl_arguments_run(self):
        morphed = os.path.join(self.dir, "m.stex")
        stex_cli.run(self.stex, stex_cli.morph_args(self.texture, self.texture, 0.5, morphed))
        shader = os.path.join(self.dir, "t.osl")
        stex_cli.run(self.stex, stex_cli.osl_args(morphed, shader))
        with open(shader) as f:
            text = f.read()
        self.assertIn("shader stochtex_t(", text)
        # The images the add-on copies beside the blend: the wavelet shader's two noise tiles and
        # the row probe every generated shader reads.
        images = stex_cli.shader_images(text)
        self.assertEqual(sorted(os.path.basename(p) for p in images),
                         ["stochtex_noise_2d.exr", "stochtex_noise_3d.exr", "stochtex_rows.exr"])
        for path in images:
            self.assertTrue(os.path.isfile(path), path)


class PureTest(unittest.TestCase):
    def test_not_stex(self):
        with self.assertRaises(stex_cli.StexError):
            stex_cli.parse_stex("{\"format\": \"png\"}")
        with self.assertRaises(stex_cli.StexError):
            stex_cli.parse_stex("{")

    def test_missing_executable_is_a_clear_error(self):
        with self.assertRaises(stex_cli.StexError) as caught:
            stex_cli.find_stex("/nonexistent/stex")
        self.assertIn("/nonexistent/stex", str(caught.exception))

    def test_error_message_prefers_stex_line(self):
        self.assertEqual(stex_cli.error_message(["warning", "stex: error: t.stex: bad"], 1), "t.stex: bad")
        self.assertIn("signal 9", stex_cli.error_message([], -9))

    def test_manifest_and_bl_info_agree(self):
        # One zip installs as a legacy add-on (bl_info) and as a 4.2+ extension (manifest).
        import ast
        import tomllib
        folder = os.path.dirname(SOURCE)
        with open(os.path.join(folder, "blender_manifest.toml"), "rb") as f:
            manifest = tomllib.load(f)
        with open(os.path.join(folder, "__init__.py")) as f:
            tree = ast.parse(f.read())
        bl_info = next(ast.literal_eval(node.value) for node in tree.body
                       if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "bl_info")
        self.assertEqual(manifest["version"], ".".join(map(str, bl_info["version"])))
        self.assertEqual(manifest["type"], "add-on")
        self.assertLessEqual(len(manifest["tagline"]), 64)
        for key in ("schema_version", "id", "name", "maintainer", "blender_version_min", "license"):
            self.assertIn(key, manifest)

    def test_option_args(self):
        options = [{"key": "filter-taps", "default": "2", "model": "tiling"}, {"key": "J", "default": "50", "model": "lrp"}]
        self.assertEqual(stex_cli.option_args("", options), [])
        self.assertEqual(stex_cli.option_args(" filter-taps=1,J=80  ", options),
                         ["--filter-taps", "1", "--J", "80"])
        self.assertEqual(stex_cli.option_args("--J=9", options), ["--J", "9"])
        for text, named in (("psd=periodic", "'psd'"), ("J", "J=50"), ("=3", "'=3'"), ("psd", "filter-taps=2"), ("J=1 J=2", "'J' is given twice")):
            with self.assertRaises(stex_cli.StexError) as caught:
                stex_cli.option_args(text, options)
            self.assertIn(named, str(caught.exception))
        with self.assertRaises(stex_cli.StexError) as caught:
            stex_cli.option_args("J=1", options[:1])
        self.assertIn("its options: filter-taps", str(caught.exception))

    def test_period(self):
        self.assertEqual(stex_cli.period_units({"scale": {"pixels_per_unit": 512}}, 1024), 2.0)

    def test_live_size_defaults_follow_the_host(self):
        self.assertEqual(stex_cli.live_size(0, streams=True), 32768)
        self.assertEqual(stex_cli.live_size(0, streams=False), 4096)
        self.assertEqual(stex_cli.live_size(2048, streams=True), 2048)

    def test_live_stex_sets_the_image_block_and_keeps_the_rest(self):
        text = json.dumps({"format": "stex", "seed": 4, "image": {"tile_width": 32, "scale": 2}})
        data = json.loads(stex_cli.live_stex(text, 8192))
        self.assertEqual(data["image"], {"tile_width": 32, "scale": 2, "width": 8192, "height": 8192})
        self.assertEqual(data["seed"], 4)
        self.assertEqual(stex_cli.image_scale(data), 2.0)
        self.assertEqual(json.loads(stex_cli.live_stex('{"format": "stex"}', 64))["image"], {"width": 64, "height": 64})
        self.assertEqual(stex_cli.image_scale({}), 1.0)

    def test_find_plugin_and_the_search_path(self):
        folder = tempfile.mkdtemp(prefix="stochtex-plugin-test-")
        try:
            with self.assertRaises(stex_cli.StexError) as caught:  # a preference naming a folder without it
                stex_cli.find_plugin(folder)
            self.assertIn(folder, str(caught.exception))
            # Beside an installed stex: PREFIX/bin/stex and PREFIX/lib/stex.imageio.so.
            os.makedirs(os.path.join(folder, "bin"))
            os.makedirs(os.path.join(folder, "lib"))
            open(os.path.join(folder, "lib", stex_cli.PLUGIN_FILE), "w").close()
            saved = os.environ.pop("STOCHTEX_PLUGIN_PATH", None)
            try:
                self.assertEqual(stex_cli.find_plugin("", os.path.join(folder, "bin", "stex")), os.path.join(folder, "lib"))
                with self.assertRaises(stex_cli.StexError) as caught:
                    stex_cli.find_plugin("", "/nonexistent/bin/stex")
                self.assertIn("add-on preferences", str(caught.exception))
            finally:
                if saved is not None:
                    os.environ["STOCHTEX_PLUGIN_PATH"] = saved
        finally:
            shutil.rmtree(folder)
        environ = {"OIIO_LIBRARY_PATH": "/a"}
        stex_cli.add_plugin_path("/p", environ)
        stex_cli.add_plugin_path("/p", environ)  # once only
        self.assertEqual(environ, {"OIIO_LIBRARY_PATH": "/p" + os.pathsep + "/a", "OPENIMAGEIO_PLUGIN_PATH": "/p"})

    def test_write_atomically_replaces_and_leaves_no_temporary(self):
        folder = tempfile.mkdtemp(prefix="stochtex-atomic-test-")
        try:
            path = os.path.join(folder, "t.stex")
            stex_cli.write_atomically(path, "one")
            stex_cli.write_atomically(path, "two")
            with open(path) as f:
                self.assertEqual(f.read(), "two")
            self.assertEqual(os.listdir(folder), ["t.stex"])
        finally:
            shutil.rmtree(folder)


if __name__ == "__main__":
    unittest.main()
