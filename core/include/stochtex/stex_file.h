// stochtex — reading and writing .stex files (JSON; docs/stex-format.md).
//
// Reading is strict: an unknown model or field, a missing field, a wrong type or array size,
// a non-finite number, an unsupported version or an inconsistent value is an Error whose
// message names the file, the field (as a JSON path) and the problem.
// Writing is canonical: write → read → write gives byte-identical files.
#pragma once

#include <stochtex/texture_description.h>

#include <string>

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
/// What is wrong with an image layout's `channels` ("expected \"RGB\", \"RGBA\" or \"Y\",
/// got …"), or "" if it is one of those: the one rule, for front-ends that name the field their way.
std::string image_channels_problem(const std::string& channels);

}  // namespace stochtex
