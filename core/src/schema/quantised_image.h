// QuantisedImage (texture_description.h): planes of floats ↔ quantised samples ↔ PNG bytes.
//
// The PNG is one grey image holding the planes stacked vertically (width × channels·height,
// 8 or 16 bits): no colour space, gamma or alpha interpretation can touch the samples, and any
// image viewer shows the exemplar's channels.
#pragma once

#include <stochtex/texture_description.h>

#include <cstdint>
#include <vector>

namespace stochtex {

/// Quantises planes (channels of width·height floats) to `bits`, each over [min, max] of its
/// own values (a constant plane gets the range [v, v]).
QuantisedImage quantise(const std::vector<std::vector<float>>& planes, int width, int height, int bits);
/// Quantises over given ranges (values outside are clamped).
QuantisedImage quantise(const std::vector<std::vector<float>>& planes, int width, int height, int bits,
                        const std::vector<std::array<double, 2>>& ranges);

/// The dequantised planes, in double.
std::vector<std::vector<double>> dequantise(const QuantisedImage& image);

std::vector<std::uint8_t> encode_png(const QuantisedImage& image);
/// Fills image.samples from PNG bytes that must hold exactly width × channels·height grey
/// samples of image.bits bits. Throws Error("<problem>").
void decode_png(const std::vector<std::uint8_t>& png, QuantisedImage& image);

}  // namespace stochtex
