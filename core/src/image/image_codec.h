// stochtex — the one interface through which the core reads and writes image files.
//
// Two codecs implement it:
//   * built in (png_codec.cpp, exr_codec.cpp): PNG through libpng and OpenEXR (scanline, and
//     tiled MIP-mapped for bakes) through the OpenEXR library, for what `stex render`, `analyze`
//     and `bake` need of the common formats. They write the same pixels and the metadata OIIO
//     wrote (tests/image_codec_test.cpp checks both directions against OIIO).
//   * OpenImageIO (core/oiio_module/oiio_codec.cpp): every other format, colour spaces other than
//     linear and sRGB, PNGs and EXRs the built-in codecs decline (gamma chunks, alpha to
//     associate, unusual channels), and the TextureSystem of `stex bench`. It is a separate
//     module, opened with dlopen on first need (codec_module.cpp): OIIO 2.4 links ~260 shared
//     libraries whose relocations alone take ~0.3 s at every start of a process that links it.
//
// Nothing here throws across the module boundary: the module reports failures as text, and the
// callers (image_io.cpp, bake.cpp, …) throw Error naming the file.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace stochtex::codec {

/// How a sample is stored in the file (pixels cross this interface as floats).
enum class Sample { u8, u16, half, f32 };

/// What a file holds, or what a writer writes: OIIO's ImageSpec, reduced to what stochtex uses.
struct ImageHeader {
    int width = 0, height = 0, channels = 0;
    int alpha_channel = -1;
    Sample sample = Sample::f32;
    std::vector<std::string> channel_names;  ///< empty: R, G, B, A by count
    /// String metadata by OIIO's names: "oiio:ColorSpace", "Software", "compression",
    /// "textureformat", "wrapmodes", "ImageDescription", "stochtex:source".
    std::vector<std::pair<std::string, std::string>> attributes;
    /// Tiled MIP-mapped output: the tile side (0: scanline).
    int tile_size = 0;

    // Inline: the module uses them too, and it links nothing of the core.
    std::string attribute(const std::string& name, const std::string& fallback = {}) const
    {
        for (const auto& [key, value] : attributes)
            if (key == name) return value;
        return fallback;
    }
    void set(const std::string& name, const std::string& value)
    {
        for (auto& [key, old] : attributes)
            if (key == name) return void(old = value);
        attributes.emplace_back(name, value);
    }
};

/// An open image file: its header, then its pixels (first subimage, level 0).
class ImageReader {
public:
    virtual ~ImageReader() = default;
    virtual const ImageHeader& header() const = 0;
    /// The first `channels` channels as floats (OIIO's conversion: integer v → v · (1/max)).
    /// Returns an empty string, or why it failed (truncated or corrupt data).
    virtual std::string read(int channels, float* pixels) = 0;
};

/// The levels of a tiled, MIP-mapped image, produced strip by strip (tile_size rows, the whole
/// width, `channels` floats a texel) as the writer asks for them.
struct MipSource {
    ImageHeader header;  ///< level 0's size; tile_size, sample, attributes for every level
    int levels = 1;
    std::function<std::pair<int, int>(int level)> level_size;
    std::function<void(int level, int y0, int rows, float* strip)> fill;
    std::function<void(double done_texels)> progress;  ///< after each strip (may be empty)
};

/// OIIO's TextureSystem, for `stex bench`'s reference route (only the module has one).
class TextureLookups {
public:
    virtual ~TextureLookups() = default;
    /// One lookup per texel of a size² grid over `file`, one-texel footprint, periodic wrap, on
    /// `threads` threads. Returns an empty string, or the error.
    virtual std::string run(const std::string& file, int size, int threads) = 0;
};

/// One implementation of image file I/O. `path` names the format (by extension); `target` is
/// where the bytes go (the AtomicOutput's temporary beside `path`).
class ImageCodec {
public:
    virtual ~ImageCodec() = default;
    virtual const char* name() const = 0;
    /// nullptr with `error` set if the file cannot be opened; nullptr with `error` empty if this
    /// codec declines a file it could open (the caller then asks the next codec). `by_name`: the
    /// caller finds the channels by their names, so their order may be the file's rather than
    /// the one OIIO would give (the built-in EXR reader then takes layered names too).
    virtual std::unique_ptr<ImageReader> open(const std::string& path, bool by_name, std::string& error) = 0;
    /// Whether `path`'s extension names a format this codec writes; `format` receives its name.
    virtual bool writes(const std::string& path, bool tiled_mip, std::string& format) = 0;
    /// Writes `pixels` (header.channels floats a pixel, top row first, stored as header.sample).
    /// Returns an empty string, or why it failed.
    virtual std::string write(const std::string& path, const std::string& target, const ImageHeader& header,
                              const float* pixels) = 0;
    virtual std::string write_mip(const std::string& path, const std::string& target, const MipSource& source) = 0;
    /// Converts `pixels` pixels of `channels` floats in place between named colour spaces;
    /// false if it does not know them (`error` says why).
    virtual bool convert_colour(float* values, std::size_t pixels, int channels, const std::string& from,
                                const std::string& to, std::string& error) = 0;
    /// nullptr where the codec has no texture system.
    virtual std::unique_ptr<TextureLookups> texture_lookups() { return nullptr; }
};

/// The built-in codecs.
ImageCodec& png_codec();
ImageCodec& exr_codec();
/// The OpenImageIO codec: registered by a front-end that links OIIO anyway (the plugin), else
/// loaded from the module on first call. Throws Error "<why> needs the OpenImageIO module
/// <file>, which cannot be loaded: <dlerror>" (why: e.g. "o.tif: writing .tif files").
ImageCodec& oiio_codec(const std::string& why);
/// For a front-end that links OIIO itself: use this codec instead of loading the module.
void register_oiio_codec(ImageCodec* codec);

/// `path` opened by the codec that reads it (chosen by the file's first bytes): built in for
/// PNG and EXR unless it declines the file, else OIIO. nullptr with `error` set if it cannot be
/// opened.
std::unique_ptr<ImageReader> open_image(const std::string& path, std::string& error, bool by_name = false);
/// The codec that writes `path`'s format (by extension; tiled_mip: as a tiled, MIP-mapped
/// image), or nullptr if none does. `format` receives the format's name where it is known.
ImageCodec* writer_for(const std::string& path, bool tiled_mip, std::string& format);

/// Whether `path` ends with `extension` (lower case, with the dot), ignoring case.
bool has_extension(const std::string& path, const char* extension);

/// The interface version the module must report (oiio_codec.cpp's stochtex_image_codec()).
constexpr int module_interface_version = 1;

}  // namespace stochtex::codec
