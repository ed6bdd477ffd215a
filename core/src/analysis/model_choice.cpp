#include "analysis/model_choice.h"

#include <stochtex/error.h>
#include <stochtex/metrics.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include "colour/chroma_given_brightness.h"
#include "colour/colour_basis.h"
#include "models/model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <set>

#include <tbb/parallel_for.h>

namespace stochtex {

namespace {

/// A fitted description and its score: a candidate's own fit or one of its variants.
struct Scored {
    TextureDescription description;
    ModelScore score;
    double penalty_without_structure = 0;  ///< the six-term penalty the default choice ranks by
};

struct Candidate {
    const Model* model = nullptr;
    ColourMode colour_mode = ColourMode::pca;
    bool joint_colour = false;
    std::vector<Scored> fits;  ///< the fit, then its variants (Model::automatic_variants)
};

/// `text` printed with `format` (one %s), for the choice's table.
std::string value_text(const char* format, const char* text)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, text);
    return buffer;
}

/// "name value" pairs of a ModelScore::variant label.
std::vector<std::pair<std::string, std::string>> variant_options(const std::string& label)
{
    std::vector<std::pair<std::string, std::string>> options;
    std::size_t start = 0;
    while (start < label.size()) {
        std::size_t end = label.find(", ", start);
        if (end == std::string::npos) end = label.size();
        const std::string pair = label.substr(start, end - start);
        const std::size_t space = pair.find(' ');
        options.emplace_back(pair.substr(0, space), space == std::string::npos ? "" : pair.substr(space + 1));
        start = end + 2;
    }
    return options;
}

/// The options a candidate is fitted with: the shared ones, and of the model options given only
/// those it declares (`--impulses 8` is gabor's and lrp's, not wavelet's).
AnalysisOptions options_for(const Model& model, ColourMode colour_mode, bool joint_colour,
                            const AnalysisOptions& options)
{
    AnalysisOptions own = options;
    own.model = model.name();
    own.colour_mode = colour_mode;
    own.joint_colour = joint_colour;
    own.try_joint_colour = false;
    own.model_options.clear();
    for (const auto& option : options.model_options)
        for (const AnalysisOption& declared : model.analysis_options())
            if (declared.info.key == option.first) own.model_options.push_back(option);
    return own;
}

}  // namespace

namespace {

/// score_against_photo, and into `without_structure` (where not null) the penalty the same
/// report gets with the six terms alone.
ModelScore score_render(const TextureDescription& description, const ComparisonReference& photo, int max_side,
                        const FidelityTargets& targets, int threads, double* without_structure)
{
    RenderSettings settings;
    settings.width = std::min(photo.width(), max_side);
    settings.height = std::min(photo.height(), max_side);
    settings.units_per_pixel = 1.0 / description.pixels_per_unit;
    settings.threads = threads;
    const Image synthesis = render(*make_texture(description), settings);
    const ComparisonReport report = compare_images(photo, synthesis);
    ModelScore score;
    score.model = description.model;
    score.colour = to_string(description.colour_mode);
    score.joint_colour = description.chroma_given_brightness.enabled();
    score.penalty = fidelity_penalty(report, targets);
    score.radial_log_psd_db = (report.log_psd_db[0] + report.log_psd_db[1] + report.log_psd_db[2]) / 3;
    score.polar_log_psd_db = report.polar_log_psd_db;
    score.w1_sigma = std::max({report.w1_relative[0], report.w1_relative[1], report.w1_relative[2]});
    score.false_colour_rate = report.false_colour_rate;
    score.gradient_orientation_degrees = report.gradient_orientation_degrees;
    score.gradient_magnitude_w1 = report.gradient_magnitude_w1;
    score.structure_distance = report.structure.total;  // NaN unless the photo's side holds structure
    score.bytes = static_cast<long long>(format_stex(description).size());
    if (without_structure) {
        FidelityTargets six = targets;
        six.structure_distance = 0;
        *without_structure = fidelity_penalty(report, six);
    }
    return score;
}

/// Whether `s` keeps every existing target the default choice `plain` keeps and, where `plain`
/// misses one, is no further from it than the metrics' own noise (model_choice_tolerance), with its 2D
/// spectrum within 10 % of `closest_2d` (the closest of the plain fits on the W1 and false-colour
/// targets) or no further than `plain`'s: what "no worse on the existing targets" asks of a
/// choice that also weighs structure (issue 33).
bool no_worse_than(const ModelScore& s, const ModelScore& plain, double closest_2d, const FidelityTargets& targets)
{
    const auto kept = [](double metric, double plain_metric, double target) {
        if (std::isnan(metric)) return std::isnan(plain_metric);
        return metric <= (plain_metric <= target ? target : (1 + model_choice_tolerance) * plain_metric);
    };
    return kept(s.radial_log_psd_db, plain.radial_log_psd_db, targets.radial_log_psd_db) &&
           kept(s.polar_log_psd_db, plain.polar_log_psd_db, targets.polar_log_psd_db) &&
           s.polar_log_psd_db <= std::max((1 + model_choice_tolerance) * closest_2d, plain.polar_log_psd_db) &&
           kept(s.w1_sigma, plain.w1_sigma, targets.w1_sigma) &&
           kept(s.false_colour_rate, plain.false_colour_rate, targets.false_colour_rate) &&
           kept(s.gradient_orientation_degrees, plain.gradient_orientation_degrees,
                targets.gradient_orientation_degrees) &&
           kept(s.gradient_magnitude_w1, plain.gradient_magnitude_w1, targets.gradient_magnitude_w1);
}

}  // namespace

ModelScore score_against_photo(const TextureDescription& description, const ComparisonReference& photo, int max_side,
                               const FidelityTargets& targets, int threads)
{
    return score_render(description, photo, max_side, targets, threads, nullptr);
}

std::size_t chosen_by_rule(const std::vector<ModelScore>& scores)
{
    double best_penalty = std::numeric_limits<double>::infinity();
    for (const ModelScore& s : scores) best_penalty = std::min(best_penalty, s.penalty);
    // A fit's variants (Model::automatic_variants) hold its data and differ from it by an option's
    // few bytes: files of one model and colour within 1 % of each other count as one size (the
    // smallest), and among equal sizes the lower penalty wins.
    const auto same_size = [](const ModelScore& a, const ModelScore& b) {
        return a.model == b.model && a.colour == b.colour && a.joint_colour == b.joint_colour &&
               std::abs(a.bytes - b.bytes) < 0.01 * double(std::max(a.bytes, b.bytes));
    };
    std::vector<long long> size(scores.size());
    for (std::size_t i = 0; i < scores.size(); ++i) {
        size[i] = scores[i].bytes;
        for (const ModelScore& other : scores)
            if (same_size(scores[i], other)) size[i] = std::min(size[i], other.bytes);
    }
    std::size_t chosen = scores.size();
    for (std::size_t i = 0; i < scores.size(); ++i) {
        if (scores[i].penalty > best_penalty * (1 + model_choice_tolerance)) continue;
        if (chosen == scores.size() || size[i] < size[chosen] ||
            (size[i] == size[chosen] && scores[i].penalty < scores[chosen].penalty))
            chosen = i;
    }
    return chosen;
}

std::size_t chosen_weighing_structure(const std::vector<ModelScore>& scores,
                                      const std::vector<double>& penalties_without_structure,
                                      const FidelityTargets& targets, const ScoreAtFullSize& at_full_size)
{
    std::vector<std::size_t> plain_rows;
    std::vector<ModelScore> plain_scores;
    double closest_2d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < scores.size(); ++i) {
        const ModelScore& s = scores[i];
        if (!s.variant.empty()) continue;  // the default's view: a variant must not tighten it
        if (s.w1_sigma <= targets.w1_sigma && s.false_colour_rate <= targets.false_colour_rate)
            closest_2d = std::min(closest_2d, s.polar_log_psd_db);
        plain_rows.push_back(i);
        plain_scores.push_back(s);
        plain_scores.back().penalty = penalties_without_structure[i];
    }
    if (plain_rows.empty()) throw Error("auto: no candidate's own fit was scored");
    const std::size_t plain = plain_rows[chosen_by_rule(plain_scores)];
    closest_2d = std::min(closest_2d, scores[plain].polar_log_psd_db);
    std::vector<std::size_t> rows;
    std::vector<ModelScore> allowed;
    for (std::size_t i = 0; i < scores.size(); ++i)
        if (i == plain || no_worse_than(scores[i], scores[plain], closest_2d, targets)) {
            rows.push_back(i);
            allowed.push_back(scores[i]);
        }
    // The scoring renders are small (max_scoring_side): they see a 1024² photo's structure and
    // low frequencies poorly. So the default's choice and the rows the rule ranks first are
    // scored again at the photo's full size, what `stex compare` and the user see: a row must
    // pass against the default's choice there too (rusted metal: a 512² γ = 4 row passed at 384²
    // and was 1.64 dB off in radial spectrum at full size, the default's 1.01), and the rule
    // decides among those by their full-size scores (sandy rock: at 384² γ = 1 and 8 on the 512²
    // exemplar are within the metrics' noise; at full size γ = 8's structure is much closer).
    if (!at_full_size || rows.size() == 1) return rows[chosen_by_rule(allowed)];
    std::vector<std::size_t> ranked(rows.size());
    for (std::size_t k = 0; k < ranked.size(); ++k) ranked[k] = k;
    std::stable_sort(ranked.begin(), ranked.end(),
                     [&](std::size_t a, std::size_t b) { return allowed[a].penalty < allowed[b].penalty; });
    const ModelScore plain_at_full_size = at_full_size(plain);
    std::vector<std::size_t> kept{plain};
    std::vector<ModelScore> kept_at_full_size{plain_at_full_size};
    int checked = 0;
    for (std::size_t k : ranked) {
        if (rows[k] == plain) continue;
        if (checked++ == max_full_size_checks) break;
        ModelScore full = at_full_size(rows[k]);
        if (!no_worse_than(full, plain_at_full_size, plain_at_full_size.polar_log_psd_db, targets)) continue;
        kept.push_back(rows[k]);
        kept_at_full_size.push_back(std::move(full));
    }
    return kept[chosen_by_rule(kept_at_full_size)];
}

TextureDescription analyze_choosing_model(const Image& photo, const AnalysisOptions& options,
                                          const ProgressCallback& progress)
{
    // The candidates: each analysable model, with each colour mode it declares worth trying
    // when the caller left the choice open.
    std::vector<Candidate> candidates;
    std::set<std::string> declared_somewhere;
    // A photo whose chroma does not vary (a grey one) has no joint colour to fit: its joint-colour
    // candidate would be the plain one again, so it is not made.
    const bool photo_has_joint_colour =
        options.try_joint_colour && has_joint_colour_to_fit(decorrelate(photo, fit_colour_basis(photo, ColourMode::pca)));
    for (const Model* model : registered_models()) {
        if (!model->info().capabilities.analysis) continue;
        std::vector<ColourMode> modes{options.colour_mode};
        if (options.try_colour_modes) {
            modes.clear();
            for (const std::string& name : model->info().automatic_colour_modes) modes.push_back(colour_mode_from_string(name));
        }
        for (ColourMode mode : modes) {
            // Joint colour, where the caller left it open and the model can carry it: both ways
            // (it removes false colour, and on some photos costs spectrum fidelity).
            const bool both = photo_has_joint_colour && mode == ColourMode::pca && model->info().capabilities.joint_colour;
            for (bool joint : both ? std::vector<bool>{false, true} : std::vector<bool>{options.joint_colour}) {
                Candidate& candidate = candidates.emplace_back();
                candidate.model = model;
                candidate.colour_mode = mode;
                candidate.joint_colour = joint;
            }
        }
        for (const AnalysisOption& option : model->analysis_options()) declared_somewhere.insert(option.info.key);
    }
    for (const auto& option : options.model_options)
        if (!declared_somewhere.count(option.first))
            throw Error("auto: unknown analysis option --" + option.first + " (no model declares it)");

    if (candidates.empty()) throw Error("auto: no registered model can analyse photos");
    std::set<std::string> given_options;  // the caller's: not varied
    for (const auto& option : options.model_options) given_options.insert(option.first);

    // The candidates side by side, one a worker: the fits are single-threaded, so this is what
    // fills the cores (each render then runs on its worker's thread; the result does not
    // depend on threads). A failure names the model it came from.
    std::mutex progress_mutex;
    std::size_t finished = 0;
    if (progress) progress(0.0, "fitting every model");
    // One photo, every candidate scored against it; the structure distance only where it scores.
    const ComparisonReference photo_side(photo, options.structure_in_choice);
    FidelityTargets targets;
    if (options.structure_in_choice) targets.structure_distance = 0.25;
    tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t i) {
        Candidate& candidate = candidates[i];
        const Model& model = *candidate.model;
        const std::string label = model.name() + " (" + to_string(candidate.colour_mode) +
                                  (candidate.joint_colour ? ", joint colour" : "") + ")";
        try {
            // The fit, then (only where structure is scored: what they change is structure) its
            // refits with other options and each one's variants.
            const AnalysisOptions own = options_for(model, candidate.colour_mode, candidate.joint_colour, options);
            std::vector<std::vector<std::pair<std::string, std::string>>> option_sets{{}};
            if (options.structure_in_choice)
                for (const auto& set : model.automatic_refits(photo.width, photo.height, given_options))
                    option_sets.push_back(set);
            for (const auto& set : option_sets) {
                AnalysisOptions refit = own;
                std::string label;
                for (const auto& option : set) {
                    refit.model_options.push_back(option);
                    std::string key = option.first;  // as the provenance names it
                    std::replace(key.begin(), key.end(), '-', '_');
                    label += (label.empty() ? "" : ", ") + key + " " + option.second;
                }
                Scored& fit = candidate.fits.emplace_back();
                fit.description = analyze_one_model(photo, refit, nullptr, &photo_side);
                fit.score = score_render(fit.description, photo_side, max_scoring_side, targets, 1,
                                         &fit.penalty_without_structure);
                fit.score.variant = label;
                if (!options.structure_in_choice) continue;
                for (FitVariant& variant : model.automatic_variants(fit.description, given_options)) {
                    Scored& varied = candidate.fits.emplace_back();
                    varied.description = std::move(variant.description);
                    varied.score = score_render(varied.description, photo_side, max_scoring_side, targets, 1,
                                                &varied.penalty_without_structure);
                    varied.score.variant = label + (label.empty() ? "" : ", ") + variant.label;
                }
            }
        } catch (const Error& e) {
            throw Error("auto: " + label + ": " + e.what());
        }
        if (!progress) return;
        const std::lock_guard<std::mutex> lock(progress_mutex);
        const std::string stage = label + " scored";
        progress(double(++finished) / double(candidates.size() + 1), stage.c_str());
    });

    std::vector<ModelScore> scores;
    std::vector<double> penalties_without_structure;
    std::vector<const Scored*> fits;
    for (const Candidate& c : candidates)
        for (const Scored& fit : c.fits) {
            scores.push_back(fit.score);
            penalties_without_structure.push_back(fit.penalty_without_structure);
            fits.push_back(&fit);
        }

    TextureDescription result =
        fits[options.structure_in_choice
                 ? chosen_weighing_structure(scores, penalties_without_structure, targets,
                                             [&](std::size_t row) {  // one at a time: every core
                                                 return score_against_photo(fits[row]->description, photo_side,
                                                                            std::max(photo.width, photo.height),
                                                                            targets, 0);
                                             })
                 : chosen_by_rule(scores)]
            ->description;
    result.provenance.model_choice = scores;
    for (auto& [name, value] : result.provenance.options)
        if (name == "model") value = automatic_model;  // what was asked; description.model says what was chosen
    if (progress) progress(1.0, "done");
    return result;
}

int chosen_model_score(const TextureDescription& description)
{
    const std::vector<ModelScore>& scores = description.provenance.model_choice;
    const auto same_fit = [&](const ModelScore& s) {
        return s.model == description.model && s.colour == to_string(description.colour_mode) &&
               s.joint_colour == description.chroma_given_brightness.enabled();
    };
    const auto& options = description.provenance.options;
    // The variant with the most options, all of which the description carries; else the fit itself.
    int row = -1;
    std::size_t row_options = 0;
    for (std::size_t i = 0; i < scores.size(); ++i) {
        if (!same_fit(scores[i])) continue;
        const auto variant = variant_options(scores[i].variant);
        bool carried = true;
        for (const auto& option : variant)
            carried = carried && std::find(options.begin(), options.end(), option) != options.end();
        if (carried && (row < 0 || variant.size() > row_options)) {
            row = int(i);
            row_options = variant.size();
        }
    }
    return row;
}

std::string format_model_choice(const TextureDescription& description)
{
    const std::vector<ModelScore>& scores = description.provenance.model_choice;
    if (scores.empty()) return {};
    const auto value = [](double v, const char* format) {
        char buffer[32];
        if (std::isnan(v)) return std::string("n/a");
        std::snprintf(buffer, sizeof buffer, format, v);
        return std::string(buffer);
    };
    // The variant and structure columns where the choice tried variants and scored structure.
    bool variants = false, structure = false;
    for (const ModelScore& s : scores) {
        variants = variants || !s.variant.empty();
        structure = structure || !std::isnan(s.structure_distance);
    }
    const auto variant_cell = [&](const ModelScore& s) {
        return variants ? value_text("%-35s ", s.variant.empty() ? "-" : s.variant.c_str()) : std::string();
    };
    const auto structure_cell = [&](const std::string& cell) {
        return structure ? value_text(" %9s", cell.c_str()) : std::string();
    };
    char line[320];
    std::string text;
    std::snprintf(line, sizeof line, "%-8s %-10s %s%8s %10s %7s %7s %12s %10s %7s%s %10s\n", "model", "colour",
                  variants ? value_text("%-35s ", "variant").c_str() : "", "penalty", "radial dB", "2D dB", "W1/σ",
                  "false colour", "orient. °", "|∇| W1", structure_cell("structure").c_str(), "bytes");
    text += line;
    const int chosen_row = chosen_model_score(description);
    for (std::size_t row = 0; row < scores.size(); ++row) {
        const ModelScore& s = scores[row];
        const bool chosen = int(row) == chosen_row;
        const std::string colour = s.colour + (s.joint_colour ? "+joint" : "");
        std::snprintf(line, sizeof line, "%-8s %-10s %s%8.3f %10s %7s %7s %12s %10s %7s%s %10lld%s\n", s.model.c_str(),
                      colour.c_str(), variant_cell(s).c_str(), s.penalty,
                      value(s.radial_log_psd_db, "%.2f").c_str(), value(s.polar_log_psd_db, "%.2f").c_str(),
                      value(s.w1_sigma, "%.3f").c_str(),
                      (value(100 * s.false_colour_rate, "%.2f") + " %").c_str(),
                      value(s.gradient_orientation_degrees, "%.2f").c_str(),
                      value(s.gradient_magnitude_w1, "%.3f").c_str(),
                      structure_cell(value(s.structure_distance, "%.3f")).c_str(), s.bytes,
                      chosen ? "  ← chosen" : "");
        text += line;
    }
    std::snprintf(line, sizeof line,
                  "rule: lowest penalty (mean of %s metric/target: radial 1.5 dB, 2D 1.5 dB, W1 0.1 σ, false colour 1 %%, "
                  "orientation 5°, |∇| 0.1%s); within %.0f %% of it, the smallest file\n",
                  structure ? "seven" : "six", structure ? ", structure 0.25" : "", 100 * model_choice_tolerance);
    text += line;
    if (structure)
        text += "      among the six-term choice and the rows no worse than it on the six targets (2D within 10 % of "
                "the closest plain fit), the first three scored again at the photo's size, where the rule decides\n";
    return text;
}

}  // namespace stochtex
