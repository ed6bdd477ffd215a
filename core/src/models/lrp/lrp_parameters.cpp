#include "models/lrp/lrp_parameters.h"
#include <stochtex/models/lrp_parameters.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace stochtex {

namespace {

using json_fields::Field;
using json_fields::Json;

/// Coefficients are written as integer multiples of the step, at most this large.
constexpr std::int64_t max_coefficient_multiple = std::int64_t(1) << 40;

std::string path_at(const std::string& path, std::size_t index) { return path + "[" + std::to_string(index) + "]"; }

std::string text(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

bool power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

/// NaN fails every range (the comparisons are written so).
void check_range(double value, double min, double max, const std::string& path, const std::string& source)
{
    if (!(value >= min && value <= max))
        json_fields::fail(source, path, "must be in [" + text(min) + ", " + text(max) + "], got " + text(value));
}

void check_count(std::size_t count, std::size_t min, std::size_t max, const char* what, const std::string& path,
                 const std::string& source)
{
    if (count < min || count > max)
        json_fields::fail(source, path,
                          "expected " + (min == max ? std::to_string(min) : std::to_string(min) + " to " + std::to_string(max)) +
                              " " + what + ", got " + std::to_string(count));
}

/// Frequency bins as flat (kx, ky) pairs, each component in [−half, half].
void check_bins(const std::vector<int>& bins, int half, std::size_t max_pairs, const std::string& path,
                const std::string& source)
{
    if (bins.size() % 2) json_fields::fail(source, path, "expected (kx, ky) pairs, got an odd count " + std::to_string(bins.size()));
    check_count(bins.size() / 2, 1, max_pairs, "frequency bins", path, source);
    for (std::size_t i = 0; i < bins.size(); ++i)
        if (bins[i] < -half || bins[i] > half)
            json_fields::fail(source, path_at(path, i),
                              "bin " + std::to_string(bins[i]) + " outside [" + std::to_string(-half) + ", " +
                                  std::to_string(half) + "]");
}

std::vector<int> read_integers(const Field& field)
{
    std::vector<int> result;
    for (const Field& item : field.elements()) result.push_back(int(item.integer(-(1 << 20), 1 << 20)));
    return result;
}

LrpStratum read_stratum(const Field& stratum)
{
    stratum.expect_keys({"spacing", "sigma", "substrata"});
    LrpStratum result;
    result.spacing = stratum["spacing"].number();
    result.sigma = stratum["sigma"].numbers<3>();
    for (const Field& substratum : stratum["substrata"].elements()) result.substrata.push_back(read_integers(substratum));
    return result;
}

LrpStructure read_structure(const Field& structure)
{
    structure.expect_keys({"block_size", "fit_size", "random_placement", "turbulence", "coefficient_step", "blocks"});
    LrpStructure result;
    result.block_size = int(structure["block_size"].integer(1, max_lrp_spectrum_size));
    result.fit_size = int(structure["fit_size"].integer(1, 2 * max_lrp_spectrum_size));
    result.random_placement = structure["random_placement"].boolean();
    result.turbulence = structure["turbulence"].number();
    result.coefficient_step = structure["coefficient_step"].number();
    for (const Field& block : structure["blocks"].elements()) {
        block.expect_keys({"frequencies", "coefficients"});
        LrpBlock b;
        b.frequencies = read_integers(block["frequencies"]);
        std::vector<Field> channels = block["coefficients"].elements(3, "channels");
        for (std::size_t c = 0; c < 3; ++c)
            for (const Field& multiple : channels[c].elements())
                b.coefficients[c].push_back(double(multiple.integer(-max_coefficient_multiple, max_coefficient_multiple)) *
                                            result.coefficient_step);
        result.blocks.push_back(std::move(b));
    }
    return result;
}

/// Cosines per evaluation point and window: Σ over strata of their sub-strata, plus the
/// structure's largest block.
int cosine_budget(const LrpParameters& parameters)
{
    int terms = 0;
    for (const LrpStratum& stratum : parameters.strata) terms += int(stratum.substrata.size());
    if (parameters.structure) {
        std::size_t largest = 0;
        for (const LrpBlock& block : parameters.structure->blocks) largest = std::max(largest, block.frequencies.size() / 2);
        terms += int(largest);
    }
    return terms;
}

}  // namespace

ParameterSchema<LrpParameters> lrp_schema()
{
    using P = LrpParameters;
    ParameterSchema<P> schema;
    schema.integer("spectrum_size", &P::spectrum_size, 1, max_lrp_spectrum_size,
                   {"", "bins", "T: frequency bins k stand for k / T cycles per exemplar pixel. The structure repeats "
                                "every T exemplar pixels.",
                    "a power of two in [4, 4096]"});
    ParameterInfo strata{"strata", "array of objects", "1 to 16 (0 when structure is present)", "", "",
                         "Random-phase strata of equal energy, each with its own lattice of windows.",
                         {{"spacing", "number", "[0.25, 1e6]", "", "exemplar px", "Δ_S: lattice spacing and window size.", {}},
                          {"sigma", "array of 3 numbers", "each ≥ 0", "", "",
                           "Standard deviation of the stratum's noise per decorrelated channel.", {}},
                          {"substrata", "array of arrays of integers", "1 to 256", "", "bins",
                           "The stratum's cosines per window. Each is a flat list of 1 to 64 bins kx0, ky0, kx1, ky1, …, "
                           "every component in [−T/2, T/2]: a lattice point draws one bin uniformly and jitters it "
                           "within its cell.",
                           {}}}};
    schema.custom(
        strata,
        [](const Field& f, P& p, const ReadContext&) {
            for (const Field& stratum : f.elements()) p.strata.push_back(read_stratum(stratum));
        },
        [](const P& parameters) {
            Json strata = Json::array();
            for (const LrpStratum& stratum : parameters.strata) {
                Json s = Json::object();
                s["spacing"] = stratum.spacing;
                s["sigma"] = stratum.sigma;
                s["substrata"] = stratum.substrata;
                strata.push_back(s);
            }
            return strata;
        });
    ParameterInfo structure{"structure", "object | null", "", "", "",
                            "The fixed-phase structure: the photo's strongest frequencies, blockwise; null for noise by "
                            "example only (r = 0).",
                            {{"block_size", "integer", "a power of two dividing T into at most 64 blocks per side", "",
                              "exemplar px", "B.", {}},
                             {"fit_size", "integer", "[B, 2T]", "", "exemplar px", "E: block frequencies are k / E cycles per "
                                                                               "exemplar pixel.", {}},
                             {"random_placement", "boolean", "", "", "",
                              "Shift cells of T/2 by random offsets (cross-faded over ⅛ cell).", {}},
                             {"turbulence", "number", "[0, T]", "", "exemplar px",
                              "Standard deviation of the displacement; 0: none.", {}},
                             {"coefficient_step", "number", "[1e-12, 1]", "", "",
                              "Block coefficients are stored as integer multiples of it (stochtex picks a power of ten "
                              "≈ 1/1000 of the largest coefficient).", {}},
                             {"blocks", "array of objects", "exactly (T/B)², row-major", "", "",
                              "{\"frequencies\": [kx0, ky0, …], \"coefficients\": [[re0, im0, …], […], […]]}: 1 to 256 "
                              "bins (components in [−E/2, E/2]) and, per channel, one re, im pair per bin as integers "
                              "n (|n| ≤ 2^40) standing for n · coefficient_step. Channel c of the block is "
                              "Σ_t re_t cos θ_t − im_t sin θ_t, θ_t = 2π k_t·(x − x_b)/E, x_b the block's centre.", {}}}};
    schema.custom(
        structure,
        [](const Field& f, P& p, const ReadContext&) {
            if (!f.is_null()) p.structure = read_structure(f);
        },
        [](const P& parameters) {
            Json structure;  // null without one
            if (!parameters.structure) return structure;
            const LrpStructure& r = *parameters.structure;
            structure["block_size"] = r.block_size;
            structure["fit_size"] = r.fit_size;
            structure["random_placement"] = r.random_placement;
            structure["turbulence"] = r.turbulence;
            structure["coefficient_step"] = r.coefficient_step;
            Json& blocks = structure["blocks"] = Json::array();
            for (const LrpBlock& block : r.blocks) {
                Json b = Json::object();
                b["frequencies"] = block.frequencies;
                Json& channels = b["coefficients"] = Json::array();
                for (const std::vector<double>& channel : block.coefficients) {
                    Json multiples = Json::array();
                    for (double c : channel) multiples.push_back(std::llround(c / r.coefficient_step));
                    channels.push_back(multiples);
                }
                blocks.push_back(b);
            }
            return structure;
        });
    // The fields depend on one another (bins within the spectrum, blocks tiling it): one check.
    schema.check([](const P& p, const std::string&, const std::string& source) { validate_lrp(p, source); });
    return schema;
}

void validate_lrp(const LrpParameters& p, const std::string& source)
{
    const int size = p.spectrum_size;
    if (!power_of_two(size) || size < 4 || size > max_lrp_spectrum_size)
        json_fields::fail(source, "parameters.spectrum_size",
                          "must be a power of two in [4, " + std::to_string(max_lrp_spectrum_size) + "], got " +
                              std::to_string(size));
    check_count(p.strata.size(), p.structure ? 0 : 1, max_lrp_strata, "strata", "parameters.strata", source);
    for (std::size_t s = 0; s < p.strata.size(); ++s) {
        const LrpStratum& stratum = p.strata[s];
        const std::string path = path_at("parameters.strata", s);
        // Below a quarter pixel a window holds no frequency the photo had; above the float range
        // of positions, lattice indices would lose precision.
        check_range(stratum.spacing, 0.25, 1e6, path + ".spacing", source);
        for (std::size_t c = 0; c < 3; ++c)
            check_range(stratum.sigma[c], 0, std::numeric_limits<float>::max(), path_at(path + ".sigma", c), source);
        check_count(stratum.substrata.size(), 1, max_lrp_terms, "sub-strata", path + ".substrata", source);
        for (std::size_t j = 0; j < stratum.substrata.size(); ++j)
            check_bins(stratum.substrata[j], size / 2, max_lrp_substratum_bins, path_at(path + ".substrata", j), source);
    }
    if (!p.structure) return;
    const LrpStructure& r = *p.structure;
    if (!power_of_two(r.block_size) || r.block_size > size || size / r.block_size > max_lrp_blocks_per_side)
        json_fields::fail(source, "parameters.structure.block_size",
                          "must be a power of two dividing spectrum_size " + std::to_string(size) + " into at most " +
                              std::to_string(max_lrp_blocks_per_side) + " blocks per side, got " +
                              std::to_string(r.block_size));
    if (r.fit_size < r.block_size || r.fit_size > 2 * size)
        json_fields::fail(source, "parameters.structure.fit_size",
                          "must be in [block_size, 2·spectrum_size] = [" + std::to_string(r.block_size) + ", " +
                              std::to_string(2 * size) + "], got " + std::to_string(r.fit_size));
    check_range(r.turbulence, 0, size, "parameters.structure.turbulence", source);
    check_range(r.coefficient_step, 1e-12, 1, "parameters.structure.coefficient_step", source);
    const std::size_t per_side = std::size_t(size / r.block_size);
    check_count(r.blocks.size(), per_side * per_side, per_side * per_side, "blocks ((spectrum_size / block_size)²)",
                "parameters.structure.blocks", source);
    for (std::size_t b = 0; b < r.blocks.size(); ++b) {
        const LrpBlock& block = r.blocks[b];
        const std::string path = path_at("parameters.structure.blocks", b);
        check_bins(block.frequencies, r.fit_size / 2, max_lrp_terms, path + ".frequencies", source);
        for (std::size_t c = 0; c < 3; ++c) {
            const std::string coefficients = path_at(path + ".coefficients", c);
            if (block.coefficients[c].size() != block.frequencies.size())
                json_fields::fail(source, coefficients,
                                  "expected " + std::to_string(block.frequencies.size()) +
                                      " numbers (re, im per frequency), got " + std::to_string(block.coefficients[c].size()));
            const double limit = double(max_coefficient_multiple) * r.coefficient_step;
            for (std::size_t i = 0; i < block.coefficients[c].size(); ++i)
                check_range(block.coefficients[c][i], -limit, limit, path_at(coefficients, i), source);
        }
    }
    if (cosine_budget(p) > 4 * max_lrp_terms)
        json_fields::fail(source, "parameters",
                          "cosine budget " + std::to_string(cosine_budget(p)) + " exceeds " +
                              std::to_string(4 * max_lrp_terms));
}

}  // namespace stochtex
