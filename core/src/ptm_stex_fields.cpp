#include "ptm_stex_fields.h"

#include "ptm_coefficient_file.h"

#include <stochtex/error.h>
#include <stochtex/ptm.h>

#include <cmath>
#include <filesystem>

namespace stochtex {

namespace fs = std::filesystem;

namespace {

constexpr double unit_tolerance = 1e-4;  // light directions are stored as floats

/// A bare file name: the maps always sit beside their .stex, so a file cannot reach elsewhere.
bool is_bare_file_name(const std::string& name)
{
    return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
           name.find('\\') == std::string::npos;
}

}  // namespace

PtmParameters read_ptm_parameters(const json_fields::Field& parameters, const std::string& stex_path)
{
    parameters.expect_keys({"colour", "light", "coefficients"}, {"unbounded"});
    PtmParameters ptm;
    const json_fields::Field colour = parameters["colour"];
    try {
        ptm.colour = ptm_colour_from_string(colour.string());
    } catch (const Error& e) {
        colour.fail(e.what());
    }
    ptm.light = parameters["light"].numbers<3>();
    const json_fields::Field coefficients = parameters["coefficients"];
    coefficients.expect_keys({"file", "width", "height", "checksum"});
    const json_fields::Field file = coefficients["file"];
    ptm.coefficient_file = file.string();
    if (!is_bare_file_name(ptm.coefficient_file))
        file.fail("expected a file name beside the .stex (no directories), got \"" + ptm.coefficient_file + "\"");
    const long long width = coefficients["width"].integer(1, max_ptm_side);
    const long long height = coefficients["height"].integer(1, max_ptm_side);
    const std::string checksum = coefficients["checksum"].string();
    const std::string path = (fs::path(stex_path).parent_path() / ptm.coefficient_file).string();
    auto maps = std::make_shared<PtmMaps>(read_ptm_coefficients(path, ptm.colour, stex_path + ": parameters.coefficients.file"));
    if (maps->width() != width || maps->height() != height)
        coefficients.fail("the file says " + std::to_string(width) + "x" + std::to_string(height) + " texels, '" +
                          ptm.coefficient_file + "' holds " + std::to_string(maps->width()) + "x" +
                          std::to_string(maps->height()));
    const std::string actual = ptm_checksum(*maps);
    if (checksum != actual)
        coefficients["checksum"].fail("\"" + checksum + "\" does not match '" + ptm.coefficient_file + "' (" + actual +
                                      "): the maps were changed or belong to another .stex");
    ptm.maps = std::move(maps);
    if (parameters.contains("unbounded")) {
        const json_fields::Field unbounded = parameters["unbounded"];
        unbounded.expect_keys({"triangle_edge"});
        ptm.unbounded = true;
        ptm.triangle_edge = unbounded["triangle_edge"].number();
    }
    return ptm;
}

void write_ptm_parameters(json_fields::Json& parameters, const PtmParameters& ptm)
{
    parameters["colour"] = to_string(ptm.colour);
    parameters["light"] = ptm.light;
    json_fields::Json& coefficients = parameters["coefficients"];
    coefficients["file"] = ptm.coefficient_file;
    coefficients["width"] = ptm.maps->width();
    coefficients["height"] = ptm.maps->height();
    coefficients["checksum"] = ptm_checksum(*ptm.maps);
    if (ptm.unbounded) parameters["unbounded"]["triangle_edge"] = ptm.triangle_edge;
}

void validate_ptm(const TextureDescription& description, const std::string& source)
{
    const PtmParameters& ptm = *description.ptm;
    auto fail = [&](const std::string& path, const std::string& problem) -> void { json_fields::fail(source, path, problem); };
    // The model has its own colour: the shared colour block must be the identity, ungraded.
    if (description.colour_mode != ColourMode::rgb) fail("colour.mode", "must be \"rgb\" for the ptm model");
    for (std::size_t c = 0; c < 3; ++c)
        if (description.histograms[c].enabled()) fail("histograms[" + std::to_string(c) + "]", "must be null for the ptm model");
    const auto& l = ptm.light;
    const double length = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    if (!(std::fabs(length - 1) <= unit_tolerance))
        fail("parameters.light", "must be a unit vector (length within 1e-4 of 1), its length is " + std::to_string(length));
    if (!(l[2] > 0)) fail("parameters.light", "must point out of the surface (z > 0)");
    if (!ptm.coefficient_file.empty() && !is_bare_file_name(ptm.coefficient_file))
        fail("parameters.coefficients.file", "must be a file name without directories");
    if (ptm.unbounded && !(ptm.triangle_edge >= 1.0 / 64 && ptm.triangle_edge <= 1))
        fail("parameters.unbounded.triangle_edge",
             "must be in [0.015625, 1] maps widths, got " + std::to_string(ptm.triangle_edge));
    if (!ptm.maps) fail("parameters.coefficients", "no coefficient maps loaded");
    const PtmMaps& maps = *ptm.maps;
    if (maps.colour != ptm.colour || maps.coefficients.channels != ptm_channel_count(ptm.colour))
        fail("parameters.coefficients", "the maps are not " + std::string(to_string(ptm.colour)) + " maps");
    if (maps.width() < 1 || maps.height() < 1 || maps.width() > max_ptm_side || maps.height() > max_ptm_side ||
        (long long)maps.width() * maps.height() > max_ptm_texels)
        fail("parameters.coefficients", "maps of " + std::to_string(maps.width()) + "x" + std::to_string(maps.height()) +
                                            " texels exceed the limits (sides 1 … 4096, at most 2^22 texels)");
}

TextureDescription write_ptm_coefficients_beside(const std::string& stex_path, const TextureDescription& description)
{
    TextureDescription named = description;
    named.ptm->coefficient_file = fs::path(stex_path).stem().string() + ".ptm.exr";
    write_ptm_coefficients((fs::path(stex_path).parent_path() / named.ptm->coefficient_file).string(), *named.ptm->maps);
    return named;
}

}  // namespace stochtex
