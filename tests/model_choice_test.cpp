// `analyze --model auto` (stochtex/analysis.h): every analysable model is fitted and scored
// against the photo, the rule picks one, and the scores travel in the provenance.
#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/metrics.h>
#include <stochtex/model.h>
#include <stochtex/models/tiling_parameters.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include "analysis/model_choice.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <array>
#include <random>
#include <string>

namespace {

using namespace stochtex;

using stochtex::test::error_of;

/// The top-left size² of the committed exemplar.
Image exemplar_crop(int size)
{
    const Image photo = read_image_linear(test::repo_exemplar("concrete_512.png"));
    Image crop(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) crop.at(x, y, c) = photo.at(x, y, c);
    return crop;
}

std::vector<std::string> analysable_models()
{
    std::vector<std::string> names;
    for (const ModelInfo* model : registered_model_infos())
        if (model->capabilities.analysis) names.push_back(model->name);
    return names;
}

/// A size² RGB photo whose pixel (x, y) is pixel(x, y, noise) (noise: a standard-normal draw).
template <class Pixel>
Image synthetic_photo(int size, unsigned seed, const Pixel& pixel)
{
    std::mt19937 random(seed);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    const auto noise = [&] { return normal(random); };
    Image photo(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const std::array<float, 3> rgb = pixel(x, y, noise);
            for (int c = 0; c < 3; ++c) photo.at(x, y, c) = rgb[c];
        }
    return photo;
}

/// Stripes across x (period 8 px, slightly wandering) over a little isotropic noise, tinted:
/// strongly oriented, which the isotropic models cannot reproduce.
Image striped_photo(int size)
{
    return synthetic_photo(size, 7, [](int x, int y, const auto& noise) {
        const double phase = 2 * M_PI * (x / 8.0 + 0.3 * std::sin(2 * M_PI * y / 97.0));
        const float v = 0.4f + 0.2f * float(std::sin(phase)) + 0.03f * noise();
        return std::array<float, 3>{v, 0.9f * v, 0.7f * v};
    });
}

/// Grains whose hue follows their brightness (dark ones blue-grey, bright ones yellow), as on
/// gravel: independent channels would make colours the photo does not have.
Image two_hue_photo(int size)
{
    return synthetic_photo(size, 11, [](int, int, const auto& noise) {
        const float t = 0.5f + 0.25f * noise();  // brightness
        const float hue = t + 0.05f * noise();
        return std::array<float, 3>{0.2f + 0.6f * t * hue, 0.2f + 0.5f * t, 0.5f - 0.3f * t * hue + 0.02f * noise()};
    });
}

TextureDescription analyse_automatically(const Image& photo)
{
    AnalysisOptions options;
    options.model = automatic_model;
    options.source_name = "photo.png";
    return analyze(photo, options);
}

TEST(ModelChoice, ScoresEveryAnalysableModelAndKeepsTheRulesChoice)
{
    const TextureDescription chosen = analyse_automatically(striped_photo(128));
    const std::vector<ModelScore>& scores = chosen.provenance.model_choice;
    ASSERT_EQ(scores.size(), analysable_models().size());
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < scores.size(); ++i) {
        EXPECT_EQ(scores[i].model, analysable_models()[i]) << "registry order";
        EXPECT_TRUE(std::isfinite(scores[i].penalty) && scores[i].penalty > 0) << scores[i].model;
        EXPECT_GT(scores[i].bytes, 0) << scores[i].model;
        best = std::min(best, scores[i].penalty);
    }
    // The rule: within the tolerance of the best penalty, the smallest file.
    const ModelScore* kept = nullptr;
    for (const ModelScore& s : scores)
        if (s.penalty <= best * (1 + model_choice_tolerance) && (!kept || s.bytes < kept->bytes)) kept = &s;
    ASSERT_NE(kept, nullptr);
    EXPECT_EQ(chosen.model, kept->model);
    // The stripes: an isotropic model (wavelet) must not be the choice; its orientation error is large.
    EXPECT_NE(chosen.model, "wavelet");
    for (const ModelScore& s : scores)
        if (s.model == "wavelet") EXPECT_GT(s.gradient_orientation_degrees, 5.0);
    // What was asked is kept beside what was chosen.
    bool recorded = false;
    for (const auto& [name, value] : chosen.provenance.options)
        if (name == "model") recorded = value == automatic_model;
    EXPECT_TRUE(recorded);
}

TEST(ModelChoice, APhotoWaveletServesKeepsTheSmallWaveletTexture)
{
    // A wavelet texture's own render is what wavelet reproduces best (up to the metrics' noise):
    // the rule's size tie-break keeps the 2 kB texture.
    AnalysisOptions options;
    options.model = "wavelet";
    const Image photo = exemplar_crop(256);
    const TextureDescription wavelet = analyze(photo, options);
    RenderSettings settings;
    settings.width = settings.height = 256;
    settings.units_per_pixel = 1.0 / wavelet.pixels_per_unit;
    const Image synthetic = render(*make_texture(wavelet), settings);
    const TextureDescription chosen = analyse_automatically(synthetic);
    EXPECT_EQ(chosen.model, "wavelet") << format_model_choice(chosen);
}

/// The candidates `auto` lists when the colour mode (and with `joint`, joint colour) is left
/// open, in registry order, as "model/mode" ("+joint" for a joint-colour row).
std::vector<std::string> expected_candidates(bool joint)
{
    std::vector<std::string> expected;
    for (const ModelInfo* model : registered_model_infos())
        if (model->capabilities.analysis)
            for (const std::string& mode : model->automatic_colour_modes) {
                expected.push_back(model->name + "/" + mode);
                if (joint && mode == "pca" && model->capabilities.joint_colour) expected.push_back(model->name + "/pca+joint");
            }
    return expected;
}

TEST(ModelChoice, LeftOpenTheColourModeIsChosenToo)
{
    AnalysisOptions options;
    options.model = automatic_model;
    options.try_colour_modes = true;
    const TextureDescription chosen = analyze(striped_photo(64), options);
    // Each model in each colour mode it declares (tiling: pca and rgb), in registry order.
    const std::vector<std::string> expected = expected_candidates(false);
    std::vector<std::string> got;
    for (const ModelScore& s : chosen.provenance.model_choice) got.push_back(s.model + "/" + s.colour);
    EXPECT_EQ(got, expected);
    EXPECT_NE(std::find(got.begin(), got.end(), "tiling/rgb"), got.end());
}

TEST(ModelChoice, LeftOpenJointColourIsTriedBothWays)
{
    // `stex analyze` without --joint-colour: each model that can carry joint colour is fitted
    // with and without it in pca colour; the table and the file say which is which, and the
    // chosen texture has joint colour exactly when its row does.
    AnalysisOptions options;
    options.model = automatic_model;
    options.try_colour_modes = true;
    options.try_joint_colour = true;
    const TextureDescription chosen = analyze(two_hue_photo(64), options);
    const std::vector<std::string> expected = expected_candidates(true);
    std::vector<std::string> got;
    bool chosen_row_found = false;
    for (const ModelScore& s : chosen.provenance.model_choice) {
        got.push_back(s.model + "/" + s.colour + (s.joint_colour ? "+joint" : ""));
        if (s.model == chosen.model && s.colour == to_string(chosen.colour_mode) &&
            s.joint_colour == chosen.chroma_given_brightness.enabled())
            chosen_row_found = true;
    }
    EXPECT_EQ(got, expected);
    EXPECT_TRUE(chosen_row_found) << format_model_choice(chosen);
    EXPECT_TRUE(test::contains(format_model_choice(chosen), "pca+joint"));
    // The flag survives the file, written only where it is set.
    const std::string text = format_stex(chosen);
    EXPECT_TRUE(test::contains(text, "\"joint_colour\": true"));
    EXPECT_FALSE(test::contains(text, "\"joint_colour\": false"));
    EXPECT_EQ(format_stex(parse_stex(text, "auto.stex")), text);
    // A photo whose chroma does not vary has no joint colour to fit: no second, identical row.
    const TextureDescription grey = analyze(striped_photo(64), options);
    for (const ModelScore& s : grey.provenance.model_choice) EXPECT_FALSE(s.joint_colour) << s.model;
}

TEST(ModelChoice, TheScoresSurviveTheFileAndAreChecked)
{
    TextureDescription chosen = analyse_automatically(striped_photo(64));
    const std::string text = format_stex(chosen);
    const TextureDescription read = parse_stex(text, "auto.stex");
    ASSERT_EQ(read.provenance.model_choice.size(), chosen.provenance.model_choice.size());
    EXPECT_EQ(format_stex(read), text) << "canonical: write, read, write is byte-identical";
    EXPECT_FALSE(format_model_choice(read).empty());

    TextureDescription bad = chosen;
    bad.provenance.model_choice[0].model = "marble";
    EXPECT_TRUE(test::contains(error_of([&] { validate(bad, "bad.stex"); }), "provenance.model_choice[0].model"));
    bad = chosen;
    bad.provenance.model_choice[0].colour = "cmyk";
    EXPECT_TRUE(test::contains(error_of([&] { validate(bad, "bad.stex"); }), "provenance.model_choice[0].colour"));
    bad = chosen;
    bad.provenance.model_choice[0].penalty = -1;
    EXPECT_TRUE(test::contains(error_of([&] { validate(bad, "bad.stex"); }), "penalty"));
}

TEST(ModelChoice, ModelOptionsGoToTheModelsThatDeclareThem)
{
    AnalysisOptions options;
    options.model = automatic_model;
    options.model_options = {{"impulses", "8"}};  // gabor's (and lrp's), not wavelet's: no error
    EXPECT_NO_THROW(analyze(striped_photo(64), options));
    options.model_options = {{"no-such-option", "1"}};
    EXPECT_TRUE(test::contains(error_of([&] { analyze(striped_photo(64), options); }), "--no-such-option"));
}

/// Opaque pebbles (discs of random size, brightness and tint, later ones over earlier ones) on a
/// dark ground: sharp-edged structure, which a γ = 1 tiling blend ghosts where tiles overlap.
Image pebble_photo(int size)
{
    std::mt19937 random(5);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    Image photo(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) photo.at(x, y, c) = 0.05f + 0.02f * uniform(random);
    for (int pebble = 0; pebble < size * size / 120; ++pebble) {
        const float cx = size * uniform(random), cy = size * uniform(random), r = 3 + 6 * uniform(random);
        const float v = 0.2f + 0.6f * uniform(random), tint = 0.8f + 0.4f * uniform(random);
        for (int y = int(cy - r); y <= int(cy + r) + 1; ++y)
            for (int x = int(cx - r); x <= int(cx + r) + 1; ++x) {
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > r * r) continue;
                const int px = (x % size + size) % size, py = (y % size + size) % size;  // periodic
                const float shade = v * (0.85f + 0.15f * (cy - y) / r);                   // lit from above
                photo.at(px, py, 0) = shade * tint;
                photo.at(px, py, 1) = shade;
                photo.at(px, py, 2) = shade / tint;
            }
    }
    return photo;
}

TEST(ModelChoice, ScoringStructureItTriesSharperTilingBlends)
{
    AnalysisOptions options;
    options.model = automatic_model;
    options.source_name = "pebbles.png";
    options.try_colour_modes = true;
    // Without the structure term: no variants, no structure column (the default's table).
    const TextureDescription plain = analyze(pebble_photo(256), options);
    for (const ModelScore& s : plain.provenance.model_choice) {
        EXPECT_TRUE(s.variant.empty()) << s.model;
        EXPECT_TRUE(std::isnan(s.structure_distance)) << s.model;
    }
    EXPECT_TRUE(test::contains(format_model_choice(plain), "mean of six"));

    options.structure_in_choice = true;
    const TextureDescription chosen = analyze(pebble_photo(256), options);
    const std::vector<ModelScore>& scores = chosen.provenance.model_choice;
    // Every tiling colour mode with γ = 1 (its fit), 4 and 8 (the fit's variants).
    std::vector<std::string> tiling_rows;
    for (const ModelScore& s : scores) {
        EXPECT_TRUE(std::isfinite(s.structure_distance) && s.structure_distance > 0) << s.model << " " << s.variant;
        if (s.model == "tiling") tiling_rows.push_back(s.colour + " [" + s.variant + "]");
        else EXPECT_TRUE(s.variant.empty()) << s.model;
    }
    EXPECT_EQ(tiling_rows, (std::vector<std::string>{"pca []", "pca [blend_contrast 4]", "pca [blend_contrast 8]",
                                                     "rgb []", "rgb [blend_contrast 4]", "rgb [blend_contrast 8]"}));
    // On the pebbles the sharper blends are closer in structure than the same exemplar at γ = 1,
    // and the choice is one of them, its row the one marked chosen.
    for (std::size_t i = 0; i + 2 < scores.size(); ++i)
        if (scores[i].model == "tiling" && scores[i].variant.empty())
            EXPECT_LT(scores[i + 2].structure_distance, scores[i].structure_distance) << scores[i].colour;
    ASSERT_EQ(chosen.model, "tiling") << format_model_choice(chosen);
    const double contrast = chosen.parameters.get<TilingParameters>().blend_contrast;
    EXPECT_GT(contrast, 1) << format_model_choice(chosen);
    const std::string table = format_model_choice(chosen);
    EXPECT_TRUE(test::contains(table, "mean of seven")) << table;
    EXPECT_TRUE(test::contains(table, "structure 0.25")) << table;
    const int row = chosen_model_score(chosen);
    ASSERT_GE(row, 0);
    EXPECT_EQ(scores[std::size_t(row)].variant, "blend_contrast " + std::to_string(int(contrast))) << table;
    // The variant and the structure distance survive the file.
    const std::string text = format_stex(chosen);
    const TextureDescription read = parse_stex(text, "auto.stex");
    EXPECT_EQ(format_stex(read), text);
    EXPECT_EQ(chosen_model_score(read), row);

    // A contrast the caller gave is not varied.
    options.model_options = {{"blend-contrast", "2"}};
    for (const ModelScore& s : analyze(pebble_photo(256), options).provenance.model_choice)
        EXPECT_TRUE(s.variant.empty()) << s.model;
}

// The structure-weighing rule's guard, on scores made up to isolate it: a variant much closer in
// structure wins only where it keeps the targets the default's choice keeps.
TEST(ModelChoice, StructureDecidesOnlyAmongFitsNoWorseOnTheExistingTargets)
{
    FidelityTargets targets;
    targets.structure_distance = 0.25;
    const auto row = [](std::string variant, double penalty, double radial, double polar, double structure) {
        ModelScore s;
        s.model = "tiling";
        s.colour = "rgb";
        s.variant = std::move(variant);
        s.penalty = penalty;
        s.radial_log_psd_db = radial;
        s.polar_log_psd_db = polar;
        s.w1_sigma = 0.05;
        s.false_colour_rate = 0.001;
        s.gradient_orientation_degrees = 1;
        s.gradient_magnitude_w1 = 0.05;
        s.structure_distance = structure;
        s.bytes = 1000;
        return s;
    };
    // The default's choice (row 0, the only plain fit), and a variant with half its structure
    // distance whose 2D distance is 20 % further (the seven-term penalty favours it).
    std::vector<ModelScore> scores{row("", 0.9, 1.0, 1.0, 0.40), row("blend_contrast 8", 0.7, 1.0, 1.2, 0.20)};
    const std::vector<double> six_term{0.5, 0.55};
    EXPECT_EQ(chosen_by_rule(scores), 1u);  // the penalty alone would take it
    EXPECT_EQ(chosen_weighing_structure(scores, six_term, targets), 0u);
    // Within 10 % of the closest 2D distance, it is the choice; the closest is the plain fits'
    // (a variant closer in 2D but not in structure does not tighten it).
    scores[1].polar_log_psd_db = 1.05;
    EXPECT_EQ(chosen_weighing_structure(scores, six_term, targets), 1u);
    scores.push_back(row("blend_contrast 4", 0.85, 1.0, 0.9, 0.38));
    const std::vector<double> six_term3{0.5, 0.55, 0.45};
    EXPECT_EQ(chosen_weighing_structure(scores, six_term3, targets), 1u);
    scores.pop_back();
    // A radial spectrum pushed off its target (the default's is on it) rules it out again.
    scores[1].radial_log_psd_db = 1.6;
    EXPECT_EQ(chosen_weighing_structure(scores, six_term, targets), 0u);
    // On its target the default's sets the bound at the target, not 10 % above the default's.
    scores[0].radial_log_psd_db = 1.4;
    scores[1].radial_log_psd_db = 1.52;
    EXPECT_EQ(chosen_weighing_structure(scores, six_term, targets), 0u);
    scores[1].radial_log_psd_db = 1.6;
    // Where the default's is off that target too, within the metrics' noise of it is allowed.
    scores[0].radial_log_psd_db = 1.55;
    EXPECT_EQ(chosen_weighing_structure(scores, six_term, targets), 1u);
    // At the photo's full size it must pass again against the default's choice there.
    std::vector<std::size_t> scored_at_full_size;
    const auto full_size = [&](double variant_radial) {
        return [&, variant_radial](std::size_t i) {
            scored_at_full_size.push_back(i);
            ModelScore s = scores[i];
            s.radial_log_psd_db = i == 0 ? 1.2 : variant_radial;
            return s;
        };
    };
    EXPECT_EQ(chosen_weighing_structure(scores, six_term, targets, full_size(1.3)), 1u);
    EXPECT_EQ(scored_at_full_size, (std::vector<std::size_t>{0, 1}));
    EXPECT_EQ(chosen_weighing_structure(scores, six_term, targets, full_size(1.7)), 0u);  // off target there
    // The rule decides among the rows ranked first by their full-size scores: a second variant,
    // second at the scoring size, is much closer at full size.
    scores.push_back(row("blend_contrast 4", 0.72, 1.0, 1.05, 0.25));
    const std::vector<double> six_term4{0.5, 0.55, 0.55};
    EXPECT_EQ(chosen_weighing_structure(scores, six_term4, targets), 1u);
    const auto second_closer = [&](std::size_t i) {
        ModelScore s = scores[i];
        s.radial_log_psd_db = 1.2;
        if (i == 2) s.penalty = 0.5;
        return s;
    };
    EXPECT_EQ(chosen_weighing_structure(scores, six_term4, targets, second_closer), 2u);
}

// Issue 14's acceptance, on every shared photo (skipped without ../shared/exemplars): the model
// `--model auto` keeps renders, at the photo's size and pixel scale as `stex compare` makes them,
// with the radial spectrum within 1.5 dB (mean over RGB), every channel's W1 within 0.10 σ and
// at most 1 % false colour; and on the scoring renders every candidate is measured on, a 2D
// spectrum no more than 10 % further from the photo's than the best candidate's among those
// that are on the W1 and false-colour targets there (gravel's PCA tiling has the closest 2D
// spectrum and 3.8 % false colour: the rule rightly passes it over).

TEST(ModelChoiceSharedExemplars, TheChoiceMeetsTheFidelityTargetsOnEveryPhoto)
{
    const std::string gravel = test::shared_exemplar("gravel.png");
    if (gravel.empty()) GTEST_SKIP() << "../shared/exemplars not found";
    std::vector<std::filesystem::path> photos;
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(gravel).parent_path()))
        if (entry.path().extension() == ".png" && entry.path().stem() != "rock_height")  // a height map, not a photo
            photos.push_back(entry.path());
    std::sort(photos.begin(), photos.end());
    ASSERT_GE(photos.size(), 9u);
    const FidelityTargets targets;
    for (const auto& path : photos) {
        SCOPED_TRACE(path.filename().string());
        const Image photo = read_image_linear(path.string());
        AnalysisOptions options;  // what `stex analyze photo.png -o t.stex` asks for
        options.model = automatic_model;
        options.try_colour_modes = true;
        options.try_joint_colour = true;
        const TextureDescription chosen = analyze(photo, options);
        const std::string table = format_model_choice(chosen);
        double best_polar = std::numeric_limits<double>::infinity();
        const ModelScore* score = nullptr;
        for (const ModelScore& s : chosen.provenance.model_choice) {
            const bool is_chosen = s.model == chosen.model && s.colour == to_string(chosen.colour_mode) &&
                                   s.joint_colour == chosen.chroma_given_brightness.enabled();
            if (is_chosen) score = &s;
            if (is_chosen || (s.w1_sigma <= targets.w1_sigma && s.false_colour_rate <= targets.false_colour_rate))
                best_polar = std::min(best_polar, s.polar_log_psd_db);
        }
        ASSERT_NE(score, nullptr) << table;
        EXPECT_LE(score->polar_log_psd_db, 1.10 * best_polar) << table;

        RenderSettings settings;
        settings.width = photo.width;
        settings.height = photo.height;
        settings.units_per_pixel = 1.0 / chosen.pixels_per_unit;
        const ComparisonReport report = compare_images(photo, render(*make_texture(chosen), settings));
        const double radial = (report.log_psd_db[0] + report.log_psd_db[1] + report.log_psd_db[2]) / 3;
        std::printf("%s: %s/%s%s, radial %.2f dB, W1 %.3f %.3f %.3f sigma, false colour %.2f %%, 2D %.2f dB\n%s",
                    path.filename().string().c_str(), chosen.model.c_str(), to_string(chosen.colour_mode),
                    chosen.chroma_given_brightness.enabled() ? "+joint" : "", radial,
                    report.w1_relative[0], report.w1_relative[1], report.w1_relative[2], 100 * report.false_colour_rate,
                    report.polar_log_psd_db, table.c_str());
        EXPECT_LE(radial, targets.radial_log_psd_db) << table;
        for (double w1 : report.w1_relative) EXPECT_LE(w1, targets.w1_sigma) << table;
        EXPECT_LE(report.false_colour_rate, targets.false_colour_rate) << table;
    }
}

TEST(FidelityPenalty, IsTheMeanOfMetricsOverTheirTargets)
{
    ComparisonReport report;
    const FidelityTargets targets;
    report.log_psd_db = {targets.radial_log_psd_db, targets.radial_log_psd_db, targets.radial_log_psd_db};
    report.polar_log_psd_db = targets.polar_log_psd_db;
    report.w1_relative = {0.0, targets.w1_sigma, 0.0};  // the worst channel counts
    report.false_colour_rate = targets.false_colour_rate;
    report.gradient_orientation_degrees = targets.gradient_orientation_degrees;
    report.gradient_magnitude_w1 = targets.gradient_magnitude_w1;
    EXPECT_DOUBLE_EQ(fidelity_penalty(report), 1.0);
    report.false_colour_rate = 1.0;  // 100 × its target: capped at 10
    EXPECT_DOUBLE_EQ(fidelity_penalty(report), (5.0 + 10.0) / 6.0);
    report.false_colour_rate = std::numeric_limits<double>::quiet_NaN();  // unmeasured counts as capped
    EXPECT_DOUBLE_EQ(fidelity_penalty(report), (5.0 + 10.0) / 6.0);
}

}  // namespace
