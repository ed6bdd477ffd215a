#include <stochtex/atomic_write.h>
#include <stochtex/error.h>
#include <stochtex/image.h>

#include "image/image_output.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
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

void convert_colour_space(Image& image, const std::string& from, const std::string& to)
{
    if (from == to || (is_scene_linear(from) && is_scene_linear(to))) return;
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf buffer(spec, image.pixels.data());
    const std::string source = is_scene_linear(from) ? "linear" : from;
    const std::string target = is_scene_linear(to) ? "linear" : to;
    if (!OIIO::ImageBufAlgo::colorconvert(buffer, buffer, source, target))
        throw Error("cannot convert colours from '" + from + "' to '" + to + "': " + buffer.geterror());
}

Image read_image_linear(const std::string& path, const ImageReadOptions& options, int min_size, ImageFileInfo* info)
{
    std::error_code ignored;
    if (!std::filesystem::exists(path, ignored)) throw Error(path + ": no such file");
    if (std::filesystem::is_directory(path, ignored)) throw Error(path + ": cannot read image: is a directory");
    auto input = OIIO::ImageInput::open(path);
    if (!input) throw Error(path + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec spec = input->spec();
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
    const int colour_channels = (alpha >= 0 && alpha < 3) ? alpha : std::min(spec.nchannels, 3);
    const int channels = std::max(1, std::min(spec.nchannels, 3));
    std::vector<float> data(std::size_t(spec.width) * spec.height * channels);
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()))
        throw Error(path + ": cannot read pixels (truncated or corrupt file?): " + input->geterror());
    // Some readers succeed with an error recorded: libjpeg decodes a truncated JPEG's missing
    // rows as flat grey and only warns ("Premature end of JPEG file").
    if (input->has_error()) throw Error(path + ": cannot read pixels (truncated or corrupt file?): " + input->geterror());
    input->close();
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
    if (colour_space.empty()) colour_space = spec.get_string_attribute("oiio:ColorSpace", "sRGB");
    try {
        convert_colour_space(image, colour_space, "linear");
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    return image;
}

void write_pixels_atomically(OIIO::ImageOutput& output, const std::string& path, const OIIO::ImageSpec& spec,
                             const float* pixels, const std::string& what)
{
    const std::string failed = path + ": cannot write " + what + ": ";
    // Where the format takes an I/O proxy the pixels go through a FILE of ours, whose error flag
    // is checked at the end: OIIO's PNG writer reports no failed write (past a file-size limit
    // it "succeeded" with a truncated file).
    AtomicOutput file(path);
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> stream(nullptr, &std::fclose);
    std::unique_ptr<OIIO::Filesystem::IOFile> proxy;
    // The caller's `output` outlives the proxy: it is closed before the proxy goes, on every
    // path (an open output's destructor would write through a dead proxy).
    struct CloseFirst {
        OIIO::ImageOutput& output;
        ~CloseFirst() { output.close(); }
    } close_first{output};
    if (output.supports("ioproxy")) {
        stream.reset(std::fopen(file.temporary().c_str(), "wb"));
        if (!stream) throw Error(failed + std::strerror(errno));
        proxy = std::make_unique<OIIO::Filesystem::IOFile>(stream.get(), OIIO::Filesystem::IOProxy::Write);
        if (!output.set_ioproxy(proxy.get())) throw Error(failed + output.geterror());
    }
    if (!output.open(file.temporary(), spec) || !output.write_image(OIIO::TypeDesc::FLOAT, pixels) || !output.close())
        throw Error(failed + output.geterror());
    if (stream) {
        const bool stream_failed = std::fflush(stream.get()) != 0 || std::ferror(stream.get());
        const std::string reason = std::strerror(errno);
        if (std::fclose(stream.release()) != 0 || stream_failed) throw Error(failed + reason);
    }
    file.commit();
}

std::unique_ptr<OIIO::ImageOutput> create_image_output(const std::string& path, const std::string& what)
{
    // The format is chosen by the final name (the temporary's ".tmp" would choose nothing).
    auto output = OIIO::ImageOutput::create(path);
    if (!output) {
        const std::string extension = std::filesystem::path(path).extension().string();
        OIIO::geterror();  // consumed: the message below says it better
        throw Error(path + ": cannot write " + what + ": " +
                    (extension.empty() ? std::string("no extension to choose a format by (e.g. .exr, .png)")
                                       : "'" + extension + "' is not an image format OpenImageIO writes (e.g. .exr, .png, .tif)"));
    }
    return output;
}

void check_image_output(const std::string& path, const std::string& what)
{
    create_image_output(path, what);
    check_output_path(path, what);
}

void write_image(const std::string& path, const Image& linear_rgb)
{
    if (linear_rgb.empty() || linear_rgb.channels != 3) throw Error(path + ": nothing to write (need an RGB image)");
    auto output = create_image_output(path, "image");
    const bool linear = is_float_format(path);
    OIIO::ImageSpec spec(linear_rgb.width, linear_rgb.height, 3, linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", linear ? "Linear" : "sRGB");
    spec.attribute("Software", "stochtex " STOCHTEX_VERSION);
    Image encoded;
    const Image* source = &linear_rgb;
    if (!linear) {
        encoded = linear_rgb;
        convert_colour_space(encoded, "linear", "sRGB");
        for (float& v : encoded.pixels) v = std::clamp(v, 0.0f, 1.0f);
        source = &encoded;
    }
    write_pixels_atomically(*output, path, spec, source->pixels.data(), "image");
}

}  // namespace stochtex
