// stochtex — float images and colour-managed image I/O.
//
// Colour spaces (see docs/colour.md):
//   * input:    what the file says (OIIO's "oiio:ColorSpace"), else sRGB; overridable.
//   * analysis: scene-linear Rec.709 primaries ("linear" in OIIO/OCIO terms). Means and MIP
//               averages are physically right only in linear light, so statistics live there.
//   * output:   EXR/TIFF/HDR keep scene-linear values; PNG/JPEG are display-encoded (sRGB).
// Conversions are OIIO's: linear ↔ sRGB computed as OIIO's built-in processors compute it, any
// other pair through OIIO's ColorConfig, i.e. OpenColorIO (loaded on first need; image_codec.h).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace stochtex {

/// A dense float image, interleaved channels, rows top to bottom.
struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;

    Image() = default;
    Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c, 0.0f) {}

    float& at(int x, int y, int c) { return pixels[(std::size_t(y) * width + x) * channels + c]; }
    float at(int x, int y, int c) const { return pixels[(std::size_t(y) * width + x) * channels + c]; }
    std::size_t pixel_count() const { return std::size_t(width) * height; }
    bool empty() const { return pixels.empty(); }

    /// One channel as a contiguous plane (width*height floats).
    std::vector<float> channel(int c) const;
};

struct ImageReadOptions {
    /// Colour space the file's values are encoded in; empty = what the file says, else "sRGB".
    std::string input_colour_space;
};

/// The largest image read_image_linear() reads: 16384 pixels a side and 2^26 pixels (a 8192²
/// photo), checked from the header before any pixel is read. Reading holds at most
/// two buffers of 3 floats per pixel (768 MiB each at the limit), and analysis a few planes more.
constexpr int max_read_side = 16384;
constexpr long long max_read_pixels = 1ll << 26;

/// What read_image_linear() found in the file besides its pixels.
struct ImageFileInfo {
    int colour_channels = 0;  ///< 1: grey (replicated into RGB), 3: colour
};

/// Reads any OIIO-readable image as scene-linear RGB (grey is replicated, alpha dropped).
/// Throws Error naming the file for: missing/unreadable file, a directory, truncated data
/// (including what the reader only warns about), images smaller than min_size or larger than
/// max_read_side / max_read_pixels, and non-finite pixel values. `info`, if given, receives
/// what the file held.
Image read_image_linear(const std::string& path, const ImageReadOptions& options = {}, int min_size = 16,
                        ImageFileInfo* info = nullptr);

/// Checks, before any work, that `path` can be written as an image: its extension names a
/// format OIIO writes (`what` says which kind of output, e.g. "image"), and its folder exists
/// and is writable. Throws Error "<path>: cannot write <what>: …". Every command that writes
/// an image calls it first, so that a typo costs nothing of a long render or bake.
void check_image_output(const std::string& path, const std::string& what = "image");

/// Writes scene-linear RGB: float EXR (and other float formats) stay linear; 8/16-bit formats
/// (PNG, JPEG, TIFF by extension) are encoded to sRGB. Throws Error on failure.
void write_image(const std::string& path, const Image& linear_rgb);

/// Converts between colour spaces known to OCIO/OIIO (e.g. "linear", "sRGB"), in place.
void convert_colour_space(Image& image, const std::string& from, const std::string& to);

/// Writes float channels as data, never colour-converted (e.g. the tables `stex osl` writes):
/// `values` holds channel_names.size() floats a pixel, top row first; zip-compressed where the
/// format compresses. Throws Error "<path>: cannot write <what>: …".
void write_data_image(const std::string& path, int width, int height, const std::vector<std::string>& channel_names,
                      const float* values, const std::string& what);

}  // namespace stochtex
