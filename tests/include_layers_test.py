#!/usr/bin/env python3
"""The include-layer check (scripts/check-include-layers.py) against docs/architecture.md's order:
it passes on the tree as it is, and it fails, naming file, line and rule, on a copy of the core
given one include against the order: a model including analysis/ (the acceptance of issue 32),
a model including another model's folder, analysis reaching into a model's folder, a public
header including core/src, a folder placed in no layer, a model including its front-end forms or
one model's forms reaching into another model; a model's forms may use the whole core. CTest `IncludeLayersSelfTest`."""
import importlib.util
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "scripts" / "check-include-layers.py"
DOCUMENT = ROOT / "docs" / "architecture.md"

spec = importlib.util.spec_from_file_location("check_include_layers", SCRIPT)
checker = importlib.util.module_from_spec(spec)
spec.loader.exec_module(checker)


class IncludeLayers(unittest.TestCase):
    def setUp(self):
        self.layers = checker.read_layers(DOCUMENT)
        self.work = Path(tempfile.mkdtemp(prefix="include-layers-"))
        self.core = self.work / "core"
        for part in ("src", "include"):
            shutil.copytree(ROOT / "core" / part, self.core / part)

    def tearDown(self):
        shutil.rmtree(self.work)

    def add_line(self, relative, text):
        """Appends `text` to core/<relative> (created if absent); returns the line's number."""
        path = self.core / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        lines = path.read_text(encoding="utf-8").splitlines() if path.exists() else []
        lines.append(text)
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        return len(lines)

    def assert_one_problem(self, *expected):
        problems = checker.check(self.core, self.layers)
        self.assertEqual(len(problems), 1, problems)
        for text in expected:
            self.assertIn(text, problems[0])

    def assert_include_fails(self, relative, included, rule):
        """core/<relative> given `#include "included"`: one problem, at that line, naming the rule."""
        line = self.add_line(relative, f'#include "{included}"')
        self.assert_one_problem(f"core/{relative}:{line}: includes {included}", rule)
        return line

    def test_the_tree_follows_its_layer_order(self):
        self.assertEqual(checker.check(ROOT / "core", self.layers), [])
        self.assertEqual(checker.check(self.core, self.layers), [])

    def test_a_model_including_analysis_fails(self):
        line = self.assert_include_fails("src/models/wavelet/wavelet_model.cpp", "analysis/model_choice.h",
                                         "src/models/wavelet is below src/analysis")
        # The command itself (what CTest `IncludeLayers` runs) exits 1 and names the include.
        run = subprocess.run([sys.executable, str(SCRIPT), "--core", str(self.core), "--layers", str(DOCUMENT)],
                             capture_output=True, text=True)
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn(f"core/src/models/wavelet/wavelet_model.cpp:{line}: includes analysis/model_choice.h", run.stdout)

    def test_a_model_header_including_analysis_fails(self):
        self.assert_include_fails("src/models/gabor/gabor_kernel.h", "analysis/structure_statistics.h", "below src/analysis")

    def test_a_model_including_another_model_fails(self):
        self.assert_include_fails("src/models/ptm/ptm_unbounded.cpp", "models/tiling/tiling_exemplar.h",
                                  "src/models/tiling is private")

    def test_analysis_reaching_into_a_model_fails(self):
        self.assert_include_fails("src/analysis/analysis.cpp", "models/wavelet/band_leakage.h", "src/models/wavelet is private")

    def test_footprint_maths_stays_below_the_models(self):
        self.assert_include_fails("src/filtering/footprint_filter.cpp", "models/model.h", "src/filtering is below src/models")

    def test_siblings_do_not_include_each_other(self):
        self.assert_include_fails("src/colour/gaussian.cpp", "spectra/fft.h", "siblings")

    def test_the_public_api_includes_no_private_header(self):
        self.assert_include_fails("include/stochtex/texture.h", "numerics/random.h", "include/stochtex is below src/numerics")

    def test_a_folder_in_no_layer_fails(self):
        self.add_line("src/somewhere/new_thing.cpp", "int new_thing() { return 0; }")
        self.assert_one_problem("core/src/somewhere/new_thing.cpp:1: in no layer")

    def test_a_models_front_end_forms_use_the_core_and_their_model(self):
        # The top layer: analysis, the registry and the model's own folder are below it.
        for included in ("analysis/model_choice.h", "models/model.h", "models/wavelet/band_leakage.h"):
            self.add_line("src/models/wavelet/front_ends/wavelet_osl.cpp", f'#include "{included}"')
        self.assertEqual(checker.check(self.core, self.layers), [])

    def test_a_front_end_form_reaching_into_another_model_fails(self):
        self.assert_include_fails("src/models/gabor/front_ends/gabor_osl.cpp", "models/wavelet/band_leakage.h",
                                  "src/models/wavelet is private")

    def test_a_model_including_its_front_end_forms_fails(self):
        self.add_line("src/models/wavelet/front_ends/wavelet_form.h", "int wavelet_form();")
        self.assert_include_fails("src/models/wavelet/wavelet_model.cpp", "front_ends/wavelet_form.h",
                                  "src/models/wavelet is below src/models/wavelet/front_ends")

    def test_front_end_forms_of_two_models_are_siblings(self):
        self.add_line("src/models/wavelet/front_ends/wavelet_form.h", "int wavelet_form();")
        self.assert_include_fails("src/models/gabor/front_ends/gabor_osl.cpp", "models/wavelet/front_ends/wavelet_form.h",
                                  "siblings")

    def test_commented_out_includes_are_not_includes(self):
        self.add_line("src/models/wavelet/wavelet_model.cpp", '// #include "analysis/model_choice.h"')
        self.assertEqual(checker.check(self.core, self.layers), [])


if __name__ == "__main__":
    unittest.main()
