#include <stochtex/atomic_write.h>
#include <stochtex/error.h>
#include <stochtex/image.h>

#include "image/colour_space_names.h"
#include "image/image_codec.h"
#include "image/image_output.h"
#include "image/png_memory.h"

// Header-only: the vectorised sRGB curves OIIO's built-in colour processors apply (no link).
#include <OpenImageIO/color.h>
#include <OpenImageIO/oiioversion.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

namespace stochtex {

namespace {

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool is_scene_linear(const std::string& colour_space)
{
    const std::string name = lower(colour_space);
    return name == "linear" || name == "scene_linear" || name == "lin_rec709" || name == "lin_srgb" ||
           name == "linear rec.709 (srgb)";
}

/// Float formats keep scene-linear values; integer formats are display-encoded.
bool is_float_format(const std::string& path)
{
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    return ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff" || ext == ".pfm";
}

}  // namespace

std::vector<float> Image::channel(int c) const
{
    std::vector<float> plane(pixel_count());
    for (std::size_t i = 0; i < plane.size(); ++i) plane[i] = pixels[i * channels + c];
    return plane;
}

namespace {

/// Whether linear ↔ sRGB can be computed here bit for bit as OIIO computes it: OIIO 2.4 without
/// an OpenColorIO config ($OCIO unset) converts between its built-in "linear" and "sRGB" with
/// OIIO::sRGB_to_linear / linear_to_sRGB on SIMD vectors of the three channels (color_ocio.cpp's
/// ColorProcessor_sRGB_to_linear); that is what this does, with the same inline functions.
/// Anything else (a config, other spaces, OIIO ≥ 2.5 whose fallback is OCIO's built-in config)
/// goes to OIIO itself (image_codec_test.cpp checks every float in [0, 1] both ways).
#if OIIO_VERSION < 20500
bool closed_form_srgb(const std::string& from, const std::string& to)
{
    const char* config = std::getenv("OCIO");
    if (config && *config) return false;
    return (from == "linear" && to == "sRGB") || (from == "sRGB" && to == "linear");
}

void convert_srgb(Image& image, bool to_linear)
{
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        float* rgb = &image.pixels[i * 3];
        OIIO::simd::vfloat4 v;
        v.load(rgb, 3);
        v = to_linear ? OIIO::sRGB_to_linear(v) : OIIO::linear_to_sRGB(v);
        v.store(rgb, 3);
    }
}
#endif

/// v^exponent for v ≥ 0; negative values pass unchanged (OCIO's ExponentTransform "pass_thru",
/// what OIIO 3.x's g18_rec709 and g22_rec709 use).
void apply_power(Image& image, double exponent)
{
    const float p = float(exponent);
    for (float& v : image.pixels)
        if (v > 0) v = std::pow(v, p);
}

}  // namespace

void convert_colour_space(Image& image, const std::string& from, const std::string& to)
{
    if (from == to || (is_scene_linear(from) && is_scene_linear(to))) return;
    std::string source = is_scene_linear(from) ? "linear" : oiio_colour_space_name(from);
    std::string target = is_scene_linear(to) ? "linear" : oiio_colour_space_name(to);
    // A gamma the linked OIIO has no name for (OIIO 3.x: all but 1.8 and 2.2) is the plain power
    // it is, applied here on the way to or from linear.
    const double decode = source.empty() ? encoding_gamma(from) : 0, encode = target.empty() ? encoding_gamma(to) : 0;
    if (decode) apply_power(image, decode), source = "linear";
    if (encode) target = "linear";
    if (source != target) {
#if OIIO_VERSION < 20500
        if (image.channels == 3 && closed_form_srgb(source, target)) {
            convert_srgb(image, source == "sRGB");
        } else
#endif
        {
            std::string error;
            if (!codec::oiio_codec("converting colours from '" + from + "' to '" + to + "'")
                     .convert_colour(image.pixels.data(), image.pixel_count(), image.channels, source, target, error))
                throw Error("cannot convert colours from '" + from + "' to '" + to + "': " + error);
        }
    }
    if (encode) apply_power(image, 1.0 / encode);
}

Image read_image_linear(const std::string& path, const ImageReadOptions& options, int min_size, ImageFileInfo* info)
{
    std::error_code ignored;
    if (!std::filesystem::exists(path, ignored)) throw Error(path + ": no such file");
    if (std::filesystem::is_directory(path, ignored)) throw Error(path + ": cannot read image: is a directory");
    std::string error;
    const auto input = codec::open_image(path, error);
    if (!input) throw Error(path + ": cannot read image: " + error);
    const codec::ImageHeader& spec = input->header();
    if (spec.width < min_size || spec.height < min_size)
        throw Error(path + ": image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                    ", too small (at least " + std::to_string(min_size) + "x" + std::to_string(min_size) + ")");
    // The header's size is checked before any pixel is read: a few bytes of header can claim
    // gigabytes of pixels.
    if (spec.width > max_read_side || spec.height > max_read_side ||
        std::int64_t(spec.width) * spec.height > max_read_pixels)
        throw Error(path + ": image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                    ", too large (at most " + std::to_string(max_read_side) + " pixels a side and " +
                    std::to_string(max_read_pixels) + " = 2^26 pixels)");
    // Only the channels used below (colour, or grey): extra channels cost no memory.
    const int alpha = spec.alpha_channel;
    const int colour_channels = (alpha >= 0 && alpha < 3) ? alpha : std::min(spec.channels, 3);
    const int channels = std::max(1, std::min(spec.channels, 3));
    std::vector<float> data(std::size_t(spec.width) * spec.height * channels);
    error = input->read(channels, data.data());
    if (!error.empty()) throw Error(path + ": cannot read pixels (truncated or corrupt file?): " + error);
    if (info) info->colour_channels = colour_channels >= 3 ? 3 : 1;

    Image image(spec.width, spec.height, 3);
    for (std::size_t i = 0; i < image.pixel_count(); ++i)
        for (int c = 0; c < 3; ++c) {
            // Grey (and grey + alpha) is replicated; alpha and extra channels are dropped.
            const float value = data[i * channels + (colour_channels >= 3 ? c : 0)];
            if (!std::isfinite(value))
                throw Error(path + ": pixel (" + std::to_string(i % spec.width) + ", " +
                            std::to_string(i / spec.width) + ") channel " + std::to_string(c) +
                            " is not a finite number");
            image.pixels[i * 3 + c] = value;
        }

    std::string colour_space = options.input_colour_space;
    if (colour_space.empty()) colour_space = spec.attribute("oiio:ColorSpace", "sRGB");
    try {
        convert_colour_space(image, colour_space, "linear");
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    return image;
}

codec::ImageCodec& image_writer(const std::string& path, const std::string& what, bool tiled_mip, std::string* format)
{
    std::string name;
    codec::ImageCodec* writer = codec::writer_for(path, tiled_mip, name);
    if (format) *format = name;
    if (writer) return *writer;
    const std::string extension = std::filesystem::path(path).extension().string();
    if (tiled_mip && !name.empty())
        throw Error(path + ": the " + name + " format cannot hold a tiled, MIP-mapped image; use .exr");
    throw Error(path + ": cannot write " + what + ": " +
                (extension.empty() ? std::string("no extension to choose a format by (e.g. .exr, .png)")
                                   : "'" + extension + "' is not an image format OpenImageIO writes (e.g. .exr, .png, .tif)"));
}

void write_image_file(const std::string& path, const codec::ImageHeader& header, const float* pixels,
                      const std::string& what)
{
    codec::ImageCodec& writer = image_writer(path, what);
    AtomicOutput file(path);
    const std::string error = writer.write(path, file.temporary(), header, pixels);
    if (!error.empty()) throw Error(path + ": cannot write " + what + ": " + error);
    file.commit();
}

void check_image_output(const std::string& path, const std::string& what)
{
    image_writer(path, what);
    check_output_path(path, what);
}

void write_image(const std::string& path, const Image& linear_rgb)
{
    if (linear_rgb.empty() || linear_rgb.channels != 3) throw Error(path + ": nothing to write (need an RGB image)");
    image_writer(path, "image");
    const bool linear = is_float_format(path);
    codec::ImageHeader header;
    header.width = linear_rgb.width, header.height = linear_rgb.height, header.channels = 3;
    header.sample = linear ? codec::Sample::f32 : codec::Sample::u8;
    header.set("oiio:ColorSpace", linear ? "Linear" : "sRGB");
    header.set("Software", "stochtex " STOCHTEX_VERSION);
    Image encoded;
    const Image* source = &linear_rgb;
    if (!linear) {
        encoded = linear_rgb;
        convert_colour_space(encoded, "linear", "sRGB");
        for (float& v : encoded.pixels) v = std::clamp(v, 0.0f, 1.0f);
        source = &encoded;
    }
    write_image_file(path, header, source->pixels.data(), "image");
}

void write_data_image(const std::string& path, int width, int height, const std::vector<std::string>& channel_names,
                      const float* values, const std::string& what)
{
    codec::ImageHeader header;
    header.width = width, header.height = height, header.channels = int(channel_names.size());
    header.channel_names = channel_names;
    header.set("compression", "zip");
    header.set("oiio:ColorSpace", "Linear");  // data, not colour: no conversion anywhere
    header.set("Software", "stochtex " STOCHTEX_VERSION);
    write_image_file(path, header, values, what);
}

namespace codec {

bool has_extension(const std::string& path, const char* extension)
{
    const std::size_t n = std::strlen(extension);
    if (path.size() < n) return false;
    for (std::size_t i = 0; i < n; ++i)
        if (std::tolower(static_cast<unsigned char>(path[path.size() - n + i])) != extension[i]) return false;
    return true;
}

std::unique_ptr<ImageReader> open_image(const std::string& path, std::string& error, bool by_name)
{
    // The format by the first bytes, as OIIO falls back to when the extension misleads.
    unsigned char magic[8] = {};
    {
        std::ifstream file(path, std::ios::binary);
        file.read(reinterpret_cast<char*>(magic), sizeof magic);
    }
    static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char exr[4] = {0x76, 0x2f, 0x31, 0x01};
    ImageCodec* built_in = std::equal(png, png + 8, magic)   ? &png_codec()
                           : std::equal(exr, exr + 4, magic) ? &exr_codec()
                                                             : nullptr;
    if (built_in) {
        auto reader = built_in->open(path, by_name, error);
        if (reader || !error.empty()) return reader;
    }
    return oiio_codec(path + ": reading " + (built_in ? std::string("this ") + built_in->name() + " file (left to OIIO)" : "its format"))
        .open(path, by_name, error);
}

ImageCodec* writer_for(const std::string& path, bool tiled_mip, std::string& format)
{
    for (ImageCodec* built_in : {&png_codec(), &exr_codec()})
        if (built_in->writes(path, tiled_mip, format)) return built_in;
    if (!format.empty()) return nullptr;  // a built-in format that cannot do what is asked
    const std::string extension = std::filesystem::path(path).extension().string();
    ImageCodec& oiio = oiio_codec(path + ": writing " + (extension.empty() ? "a file without an extension" : "'" + extension + "' files"));
    return oiio.writes(path, tiled_mip, format) ? &oiio : nullptr;
}

}  // namespace codec

}  // namespace stochtex
