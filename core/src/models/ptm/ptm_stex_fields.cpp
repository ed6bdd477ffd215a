#include "models/ptm/ptm_stex_fields.h"

#include "models/ptm/ptm_coefficient_file.h"

#include <stochtex/error.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/ptm_parameters.h>

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

namespace {

/// The coefficient maps: named in the .stex, loaded from beside it, checked against its size
/// and checksum.
void read_coefficients(const json_fields::Field& coefficients, PtmParameters& ptm, const ReadContext& context)
{
    coefficients.expect_keys({"file", "width", "height", "checksum"});
    const json_fields::Field file = coefficients["file"];
    ptm.coefficient_file = file.string();
    if (!is_bare_file_name(ptm.coefficient_file))
        file.fail("expected a file name beside the .stex (no directories), got \"" + ptm.coefficient_file + "\"");
    const long long width = coefficients["width"].integer(1, max_ptm_side);
    const long long height = coefficients["height"].integer(1, max_ptm_side);
    const std::string checksum = coefficients["checksum"].string();
    const std::string path = (fs::path(context.stex_path).parent_path() / ptm.coefficient_file).string();
    auto maps = std::make_shared<PtmMaps>(
        read_ptm_coefficients(path, ptm.colour, context.stex_path + ": parameters.coefficients.file"));
    if (maps->width() != width || maps->height() != height)
        coefficients.fail("the file says " + std::to_string(width) + "x" + std::to_string(height) + " texels, '" +
                          ptm.coefficient_file + "' holds " + std::to_string(maps->width()) + "x" +
                          std::to_string(maps->height()));
    const std::string actual = ptm_checksum(*maps);
    if (checksum != actual)
        coefficients["checksum"].fail("\"" + checksum + "\" does not match '" + ptm.coefficient_file + "' (" + actual +
                                      "): the maps were changed or belong to another .stex");
    ptm.maps = std::move(maps);
}

void check_coefficients(const PtmParameters& ptm, const std::string& path, const std::string& source)
{
    if (!ptm.coefficient_file.empty() && !is_bare_file_name(ptm.coefficient_file))
        json_fields::fail(source, path + ".file", "must be a file name without directories");
    if (!ptm.maps) json_fields::fail(source, path, "no coefficient maps loaded");
    const PtmMaps& maps = *ptm.maps;
    if (maps.colour != ptm.colour || maps.coefficients.channels != ptm_channel_count(ptm.colour))
        json_fields::fail(source, path, "the maps are not " + std::string(to_string(ptm.colour)) + " maps");
    if (maps.width() < 1 || maps.height() < 1 || maps.width() > max_ptm_side || maps.height() > max_ptm_side ||
        (long long)maps.width() * maps.height() > max_ptm_texels)
        json_fields::fail(source, path,
                          "maps of " + std::to_string(maps.width()) + "x" + std::to_string(maps.height()) +
                              " texels exceed the limits (sides 1 … 4096, at most 2^22 texels)");
}

}  // namespace

ParameterSchema<PtmParameters> ptm_schema()
{
    using P = PtmParameters;
    ParameterSchema<P> schema;
    schema.enumeration("colour", &P::colour, to_string, ptm_colour_from_string, {PtmColour::lrgb, PtmColour::rgb},
                       {"lrgb", "", "lrgb: one luminance function times a per-texel chroma (9 channels); rgb: one function "
                                   "per channel (18 channels)."});
    schema.numbers("light", &P::light, {}, {"[0, 0, 1]", "", "The light direction the texture is evaluated for: x to the "
                                                           "image's right, y to its top, z out of the surface (open-time "
                                                           "hint stex:light, stex ptm relight --light).",
                                                     "unit vector, z > 0"},
                   [](const P& ptm, const std::string& path, const std::string& source) {
                       const auto& l = ptm.light;
                       const double length = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
                       if (!(std::fabs(length - 1) <= unit_tolerance))
                           json_fields::fail(source, path,
                                             "must be a unit vector (length within 1e-4 of 1), its length is " +
                                                 std::to_string(length));
                       if (!(l[2] > 0)) json_fields::fail(source, path, "must point out of the surface (z > 0)");
                   });
    ParameterInfo coefficients{"coefficients", "object", "", "", "",
                               "The coefficient maps: a float EXR beside the .stex (see below).",
                               {{"file", "string", "a file name without directories (no / or \\; not . or ..)",
                                 "NAME.ptm.exr", "", "Must exist beside the .stex; write_stex writes it as NAME.ptm.exr for NAME.stex.", {}},
                                {"width", "integer", "[1, 4096]", "", "texels", "Must equal the file's.", {}},
                                {"height", "integer", "[1, 4096]", "", "texels", "Must equal the file's.", {}},
                                {"checksum", "string", "\"fnv1a64:\" and 16 hex digits", "", "",
                                 "FNV-1a over the width, height, channel count and the floats' bits in channel order; must "
                                 "match the file (a stale or foreign file is an error, not a different texture).", {}}}};
    schema.custom(
        coefficients, read_coefficients,
        [](const P& ptm) {
            json_fields::Json json;
            json["file"] = ptm.coefficient_file;
            json["width"] = ptm.maps->width();
            json["height"] = ptm.maps->height();
            json["checksum"] = ptm_checksum(*ptm.maps);
            return json;
        },
        check_coefficients);
    ParameterInfo unbounded{"unbounded", "object", "", "", "",
                            "Present: the texture is unbounded — the maps tiled and blended over a triangle grid with one "
                            "set of tiles for all coefficients, seeded by seed (the maps should tile). Absent: the maps "
                            "repeat.",
                            {{"triangle_edge", "number", "[0.015625, 1]", "", "maps widths",
                              "The grid's edge in widths of the maps' shorter side.", {}}}};
    schema.optional_custom(
        unbounded, [](const P& ptm) { return ptm.unbounded; },
        [](const json_fields::Field& f, P& ptm, const ReadContext&) {
            f.expect_keys({"triangle_edge"});
            ptm.unbounded = true;
            ptm.triangle_edge = f["triangle_edge"].number();
        },
        [](const P& ptm) {
            json_fields::Json json;
            json["triangle_edge"] = ptm.triangle_edge;
            return json;
        },
        [](const P& ptm, const std::string& path, const std::string& source) {
            if (!(ptm.triangle_edge >= 1.0 / 64 && ptm.triangle_edge <= 1))
                json_fields::fail(source, path + ".triangle_edge",
                                  "must be in [0.015625, 1] maps widths, got " + std::to_string(ptm.triangle_edge));
        });
    return schema;
}

void validate_ptm_colour_fields(const TextureDescription& description, const std::string& source)
{
    // The model has its own colour: the shared colour block must be the identity, ungraded.
    if (description.colour_mode != ColourMode::rgb) json_fields::fail(source, "colour.mode", "must be \"rgb\" for the ptm model");
    for (std::size_t c = 0; c < 3; ++c)
        if (description.histograms[c].enabled())
            json_fields::fail(source, "histograms[" + std::to_string(c) + "]", "must be null for the ptm model");
}

TextureDescription write_ptm_coefficients_beside(const std::string& stex_path, const TextureDescription& description)
{
    TextureDescription named = description;
    named.parameters.get<PtmParameters>().coefficient_file = fs::path(stex_path).stem().string() + ".ptm.exr";
    write_ptm_coefficients((fs::path(stex_path).parent_path() / named.parameters.get<PtmParameters>().coefficient_file).string(), *named.parameters.get<PtmParameters>().maps);
    return named;
}

}  // namespace stochtex
