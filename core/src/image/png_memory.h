// stochtex — grey PNGs in memory: the quantised planes embedded in .stex files
// (schema/quantised_image.cpp), through the built-in PNG codec.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace stochtex::codec {

/// A grey PNG of 8- or 16-bit `samples` (width·height, top row first), as OIIO encoded it at
/// compression level 9: the same image always gives the same bytes. Throws on failure.
std::vector<std::uint8_t> encode_grey_png(int width, int height, int bits, const std::uint16_t* samples);

/// The PNG's size, channel count and sample bits; with `samples`, its pixels too (grey only).
/// Returns an empty string, or the problem ("unreadable PNG: …", "truncated or corrupt PNG: …").
std::string decode_grey_png(const std::vector<std::uint8_t>& png, int& width, int& height, int& channels, int& bits,
                            std::vector<std::uint16_t>* samples);

}  // namespace stochtex::codec
