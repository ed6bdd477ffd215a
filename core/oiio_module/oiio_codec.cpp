// stochtex — the OpenImageIO codec (image_codec.h): every format, colour space and texture
// lookup the built-in codecs do not cover. Built twice from this file: as the module
// stochtex_oiio.so that the core opens with dlopen on first need (exported entry point
// stochtex_image_codec()), and into front-ends that link OIIO anyway (the plugin), which
// register it at static initialisation (STOCHTEX_OIIO_CODEC_STATIC).
//
// Self-contained: it uses only OIIO and the interface header, never the core (which lives in
// the executable that loads it), and reports failures as text.
#include "image/image_codec.h"
#include "image/private_texture_system.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace stochtex::codec {

namespace {

OIIO::TypeDesc type_of(Sample sample)
{
    switch (sample) {
    case Sample::u8: return OIIO::TypeDesc::UINT8;
    case Sample::u16: return OIIO::TypeDesc::UINT16;
    case Sample::half: return OIIO::TypeDesc::HALF;
    case Sample::f32: break;
    }
    return OIIO::TypeDesc::FLOAT;
}

Sample sample_of(OIIO::TypeDesc type)
{
    if (type == OIIO::TypeDesc::UINT8) return Sample::u8;
    if (type == OIIO::TypeDesc::UINT16) return Sample::u16;
    if (type == OIIO::TypeDesc::HALF) return Sample::half;
    return Sample::f32;
}

/// The ImageSpec a header describes. "openexr:levelmode"/"openexr:roundingmode" are integers in
/// OIIO; every other attribute is a string.
OIIO::ImageSpec spec_of(const ImageHeader& header, int width, int height)
{
    OIIO::ImageSpec spec(width, height, header.channels, type_of(header.sample));
    if (!header.channel_names.empty()) spec.channelnames = header.channel_names;
    spec.alpha_channel = header.alpha_channel;
    if (header.tile_size > 0) spec.tile_width = spec.tile_height = header.tile_size;
    for (const auto& [name, value] : header.attributes) spec.attribute(name, value);
    return spec;
}

class OiioReader final : public ImageReader {
public:
    explicit OiioReader(std::unique_ptr<OIIO::ImageInput> input) : input_(std::move(input))
    {
        const OIIO::ImageSpec& spec = input_->spec();
        header_.width = spec.width;
        header_.height = spec.height;
        header_.channels = spec.nchannels;
        header_.alpha_channel = spec.alpha_channel;
        header_.sample = sample_of(spec.format);
        header_.channel_names = spec.channelnames;
        const std::string colour_space = spec.get_string_attribute("oiio:ColorSpace");
        if (!colour_space.empty()) header_.set("oiio:ColorSpace", colour_space);
    }
    const ImageHeader& header() const override { return header_; }
    std::string read(int channels, float* pixels) override
    {
        if (!input_->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels)) return input_->geterror();
        // Some readers succeed with an error recorded: libjpeg decodes a truncated JPEG's missing
        // rows as flat grey and only warns ("Premature end of JPEG file").
        if (input_->has_error()) return input_->geterror();
        input_->close();
        return {};
    }

private:
    std::unique_ptr<OIIO::ImageInput> input_;
    ImageHeader header_;
};

/// An ImageOutput for `path`'s format writing to `target`; `write(output)` does the opens and
/// writes. With `proxy`, where the format takes one, the bytes go through a FILE of ours whose
/// error flag is checked at the end: OIIO's PNG writer reports no failed write (past a
/// file-size limit it "succeeded" with a truncated file).
template <class Write>
std::string write_through(const std::string& path, const std::string& target, bool proxy, Write write)
{
    // Declared before the output, so destroyed after it: an output still open when an error
    // returns early writes through them as it closes.
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> stream(nullptr, &std::fclose);
    std::unique_ptr<OIIO::Filesystem::IOFile> io;
    // The format is chosen by the final name (the temporary's ".tmp" would choose nothing).
    auto output = OIIO::ImageOutput::create(path);
    if (!output) return OIIO::geterror();
    if (proxy && output->supports("ioproxy")) {
        stream.reset(std::fopen(target.c_str(), "wb"));
        if (!stream) return std::strerror(errno);
        io = std::make_unique<OIIO::Filesystem::IOFile>(stream.get(), OIIO::Filesystem::IOProxy::Write);
        if (!output->set_ioproxy(io.get())) return output->geterror();
    }
    std::string error = write(*output);
    if (!error.empty()) return error;
    if (!output->close()) return output->geterror();
    output.reset();
    if (stream) {
        const bool stream_failed = std::fflush(stream.get()) != 0 || std::ferror(stream.get());
        const std::string reason = std::strerror(errno);
        if (std::fclose(stream.release()) != 0 || stream_failed) return reason;
    }
    return {};
}

class OiioTextureLookups final : public TextureLookups {
public:
    OiioTextureLookups() : system_(make_private_texture_system()) {}

    std::string run(const std::string& path, int size, int threads) override
    {
        const OIIO::ustring file(path);
        const float texel = 1.0f / float(size);
        std::atomic<int> next{0};
        std::string failure;
        std::mutex mutex;
        auto work = [&] {
            OIIO::TextureOpt options;
            options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
            OIIO::TextureSystem::Perthread* thread = system_->get_perthread_info();
            OIIO::TextureSystem::TextureHandle* handle = system_->get_texture_handle(file, thread);
            float rgb[3];
            for (int row; (row = next.fetch_add(1)) < size;)
                for (int x = 0; x < size; ++x)
                    if (!system_->texture(handle, thread, options, (x + 0.5f) * texel, (row + 0.5f) * texel, texel, 0, 0,
                                          texel, 3, rgb)) {
                        const std::lock_guard<std::mutex> lock(mutex);
                        if (failure.empty()) failure = system_->geterror();
                        next = size;
                        return;
                    }
        };
        std::vector<std::thread> workers;
        for (int t = 0; t < std::min(threads, size); ++t) workers.emplace_back(work);
        for (std::thread& worker : workers) worker.join();
        return failure.empty() ? std::string() : "TextureSystem lookup in " + path + " failed: " + failure;
    }

private:
    PrivateTextureSystem system_;
};

class OiioCodec final : public ImageCodec {
public:
    const char* name() const override { return "OpenImageIO"; }

    std::unique_ptr<ImageReader> open(const std::string& path, bool, std::string& error) override
    {
        auto input = OIIO::ImageInput::open(path);
        if (!input) {
            error = OIIO::geterror();
            if (error.empty()) error = "unknown image format";
            return nullptr;
        }
        return std::make_unique<OiioReader>(std::move(input));
    }

    bool writes(const std::string& path, bool tiled_mip, std::string& format) override
    {
        auto output = OIIO::ImageOutput::create(path);
        if (!output) {
            OIIO::geterror();  // consumed: the caller says it better
            return false;
        }
        format = output->format_name();
        return !tiled_mip || (output->supports("tiles") && output->supports("mipmap"));
    }

    std::string write(const std::string& path, const std::string& target, const ImageHeader& header,
                      const float* pixels) override
    {
        const OIIO::ImageSpec spec = spec_of(header, header.width, header.height);
        return write_through(path, target, true, [&](OIIO::ImageOutput& output) -> std::string {
            if (!output.open(target, spec) || !output.write_image(OIIO::TypeDesc::FLOAT, pixels)) return output.geterror();
            return {};
        });
    }

    std::string write_mip(const std::string& path, const std::string& target, const MipSource& source) override
    {
        const int tile = source.header.tile_size, channels = source.header.channels;
        double done = 0;
        // Without a proxy, as stochtex always wrote its bakes: OIIO 2.4's EXR writer, appending
        // MIP levels through one, crashed in its destructor (tellp() on the proxy) in
        // image_codec_test.
        return write_through(path, target, false, [&](OIIO::ImageOutput& output) -> std::string {
            for (int level = 0; level < source.levels; ++level) {
                const auto [width, height] = source.level_size(level);
                OIIO::ImageSpec spec = spec_of(source.header, width, height);
                spec.attribute("openexr:levelmode", 1);     // MIPMAP_LEVELS: our levels, not generated ones
                spec.attribute("openexr:roundingmode", 0);  // ROUND_DOWN: sizes halve as MipImage's do
                const auto mode = level == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendMIPLevel;
                if (!output.open(target, spec, mode))
                    return "cannot write MIP level " + std::to_string(level) + ": " + output.geterror();
                std::vector<float> strip(std::size_t(width) * tile * channels);
                for (int y0 = 0; y0 < height; y0 += tile) {
                    const int rows = std::min(tile, height - y0);
                    source.fill(level, y0, rows, strip.data());
                    if (!output.write_tiles(0, width, y0, y0 + rows, 0, 1, OIIO::TypeDesc::FLOAT, strip.data()))
                        return "cannot write tiles: " + output.geterror();
                    done += double(width) * rows;
                    if (source.progress) source.progress(done);
                }
            }
            return {};
        });
    }

    bool convert_colour(float* values, std::size_t pixels, int channels, const std::string& from, const std::string& to,
                        std::string& error) override
    {
        OIIO::ImageSpec spec(int(pixels), 1, channels, OIIO::TypeDesc::FLOAT);
        OIIO::ImageBuf buffer(spec, values);
        if (OIIO::ImageBufAlgo::colorconvert(buffer, buffer, from, to)) return true;
        error = buffer.geterror();
        return false;
    }

    std::unique_ptr<TextureLookups> texture_lookups() override { return std::make_unique<OiioTextureLookups>(); }
};

}  // namespace

}  // namespace stochtex::codec

#ifdef STOCHTEX_OIIO_CODEC_STATIC
namespace {
// Linked into a front-end that has OIIO already: no module to load.
const bool registered = [] {
    static stochtex::codec::OiioCodec codec;
    stochtex::codec::register_oiio_codec(&codec);
    return true;
}();
}  // namespace
#else
/// The module's entry point (codec_module.cpp): the codec, or nullptr if the interface the
/// loader expects is not the one this module was built with.
extern "C" __attribute__((visibility("default"))) stochtex::codec::ImageCodec* stochtex_image_codec(int interface_version)
{
    if (interface_version != stochtex::codec::module_interface_version) return nullptr;
    static stochtex::codec::OiioCodec codec;
    return &codec;
}
#endif
