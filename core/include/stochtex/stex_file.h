// stochtex — reading and writing .stex files (JSON; docs/stex-format.md).
//
// Reading is strict: an unknown model or field, a missing field, a wrong type or array size,
// a non-finite number, an unsupported version or an inconsistent value is an Error whose
// message names the file, the field (as a JSON path) and the problem.
// Writing is canonical: write → read → write gives byte-identical files.
#pragma once

#include <stochtex/model.h>
#include <stochtex/texture_description.h>

#include <string>
#include <variant>
#include <vector>

namespace stochtex {

TextureDescription read_stex(const std::string& path);
/// Parses .stex text; `source_name` is used in error messages (usually the file name).
TextureDescription parse_stex(const std::string& text, const std::string& source_name);

std::string format_stex(const TextureDescription& description);
void write_stex(const std::string& path, const TextureDescription& description);

/// Semantic checks shared by the reader and by code that builds descriptions (analysis, morph):
/// sizes, finiteness, orthonormal basis, monotone histograms. Throws Error naming `source_name`.
void validate(const TextureDescription& description, const std::string& source_name);
/// The checks of the optional "image" block alone (for layouts overridden at open time).
void validate_image_layout(const ImageLayout& image, const std::string& source_name);

/// A block of the .stex file that is the same whatever the model (scale, colour, histograms,
/// provenance, image), as declared once in the core: its JSON path and its fields. The tables of
/// docs/stex-format.md are made from these (parameter_table_markdown).
struct StexBlockInfo {
    std::string path;  ///< "scale", "colour", "histograms[c]", "provenance", "image"
    std::vector<ParameterInfo> fields;
};
/// The shared blocks, in file order.
std::vector<StexBlockInfo> shared_stex_blocks();

/// The fields of the "image" block as declared (key, type, range, default, doc). A host's
/// open-time hints are these keys (the OIIO plugin's "stex:" + key), so a field declared there
/// is a hint everywhere without another list.
const std::vector<ParameterInfo>& image_layout_fields();
/// A value for one field of an image layout as a host gives it: an integer, a number or a string.
using ImageLayoutValue = std::variant<long long, double, std::string>;
/// Sets the field `key` (one of image_layout_fields()) of `layout`. Throws Error naming `source`
/// for an unknown key or a value of another type than the field's (checks of the value itself
/// are image_layout_field_problem()'s and validate_image_layout()'s).
void set_image_layout_field(ImageLayout& layout, const std::string& key, const ImageLayoutValue& value,
                            const std::string& source);
/// What is wrong with the field `key` of `layout` that the field alone tells (an unknown channel
/// layout: "expected \"RGB\", \"RGBA\" or \"Y\", got …"), or "": for front-ends that name the field
/// their way. Relations between fields (tiles against sides, the pixel count) are
/// validate_image_layout()'s.
std::string image_layout_field_problem(const ImageLayout& layout, const std::string& key);

}  // namespace stochtex
