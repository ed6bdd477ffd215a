// Base64 (RFC 4648, standard alphabet, padded): how binary payloads (a tiling texture's exemplar
// PNG) travel inside a JSON .stex file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace stochtex {

std::string base64_encode(const std::vector<std::uint8_t>& bytes);

/// Strict: only the standard alphabet, length a multiple of 4, '=' only as final padding, no
/// whitespace. Throws Error("<problem>") (the caller prefixes the field's path).
std::vector<std::uint8_t> base64_decode(const std::string& text);

}  // namespace stochtex
