// stochtex — the built-in PNG codec (image_codec.h), libpng directly.
//
// It reads what OIIO's PNG reader reads the same way without any colour or alpha decision:
// 8- and 16-bit grey, RGB and palette images, non-interlaced, with no gamma but sRGB's. It
// declines the rest (alpha, which OIIO associates on reading; gAMA chunks, which make OIIO name
// a "GammaX.Y" colour space; bit depths below 8; interlacing) so that OIIO reads those as before.
// It writes as OIIO's PNG writer does, chunk for chunk (IHDR, sRGB, oFFs, tEXt, IDAT), so the
// quantised planes embedded in .stex files keep their bytes (tests/image_codec_test.cpp).
#include "image/image_codec.h"
#include "image/png_memory.h"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

namespace stochtex::codec {

namespace {

/// libpng reports errors by longjmp; the message is kept here first.
struct PngErrors {
    std::string message;
    static void error(png_structp png, png_const_charp text)
    {
        static_cast<PngErrors*>(png_get_error_ptr(png))->message = text;
        png_longjmp(png, 1);
    }
    static void warning(png_structp, png_const_charp) {}
};

/// Bytes in, from a FILE or from memory.
struct Source {
    std::FILE* file = nullptr;
    const std::uint8_t* data = nullptr;
    std::size_t size = 0, at = 0;
    static void read(png_structp png, png_bytep out, png_size_t count)
    {
        auto* source = static_cast<Source*>(png_get_io_ptr(png));
        if (source->file) {
            if (std::fread(out, 1, count, source->file) != count) png_error(png, "unexpected end of file");
        } else {
            if (source->size - source->at < count) png_error(png, "unexpected end of data");
            std::memcpy(out, source->data + source->at, count);
            source->at += count;
        }
    }
};

/// Bytes out, to a FILE (error flag checked at the end) or to memory.
struct Sink {
    std::FILE* file = nullptr;
    std::vector<std::uint8_t>* bytes = nullptr;
    static void write(png_structp png, png_bytep in, png_size_t count)
    {
        auto* sink = static_cast<Sink*>(png_get_io_ptr(png));
        if (sink->file) {
            if (std::fwrite(in, 1, count, sink->file) != count) png_error(png, std::strerror(errno));
        } else {
            sink->bytes->insert(sink->bytes->end(), in, in + count);
        }
    }
    static void flush(png_structp) {}
};

/// A decoded PNG: the rows as libpng gives them (8- or 16-bit samples, native byte order).
struct Decoded {
    ImageHeader header;
    std::vector<std::uint8_t> rows;
    bool declined = false;
};

/// Reads the header and, if `pixels`, the pixels. An error leaves `errors.message` set. With
/// `decline`, what the built-in reader leaves to OIIO sets out.declined instead.
bool decode(Source& source, bool pixels, Decoded& out, PngErrors& errors, bool decline = true)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, &PngErrors::error, &PngErrors::warning);
    if (!png) return errors.message = "out of memory", false;
    png_infop info = png_create_info_struct(png);
    struct Destroy {
        png_structp* png;
        png_infop* info;
        ~Destroy() { png_destroy_read_struct(png, info, nullptr); }
    } destroy{&png, &info};
    if (!info) return errors.message = "out of memory", false;
    // Every C++ object the longjmp below may skip is built before the setjmp.
    std::vector<png_bytep> rows;
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_read_fn(png, &source, &Source::read);
    png_read_info(png, info);
    png_uint_32 width = 0, height = 0;
    int depth = 0, colour = 0, interlace = 0;
    png_get_IHDR(png, info, &width, &height, &depth, &colour, &interlace, nullptr, nullptr);
    const bool gamma = png_get_valid(png, info, PNG_INFO_gAMA) && !png_get_valid(png, info, PNG_INFO_sRGB);
    bool colour_space_text = false;
    png_textp text = nullptr;
    int texts = 0;
    png_get_text(png, info, &text, &texts);
    for (int i = 0; i < texts; ++i)
        colour_space_text |= std::strcmp(text[i].key, "oiio:ColorSpace") == 0 && std::strcmp(text[i].text, "sRGB") != 0;
    if (decline && ((colour & PNG_COLOR_MASK_ALPHA) || png_get_valid(png, info, PNG_INFO_tRNS) || gamma || colour_space_text ||
        (depth < 8 && colour != PNG_COLOR_TYPE_PALETTE) || interlace != PNG_INTERLACE_NONE)) {
        out.declined = true;
        return true;
    }
    out.header.width = int(width);
    out.header.height = int(height);
    out.header.channels = (colour == PNG_COLOR_TYPE_GRAY ? 1 : colour == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : colour == PNG_COLOR_TYPE_RGB ? 3 : 4) -
                          (colour == PNG_COLOR_TYPE_PALETTE && !png_get_valid(png, info, PNG_INFO_tRNS));
    out.header.sample = depth == 16 ? Sample::u16 : Sample::u8;
    out.header.set("oiio:ColorSpace", "sRGB");
    if (!pixels) return true;
    if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (colour == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (depth == 16) png_set_swap(png);  // native (little-endian) 16-bit samples
    png_read_update_info(png, info);
    const std::size_t stride = png_get_rowbytes(png, info);
    out.rows.resize(stride * height);
    rows.resize(height);
    for (png_uint_32 y = 0; y < height; ++y) rows[y] = out.rows.data() + y * stride;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    return true;
}

void to_float(const Decoded& decoded, int channels, float* pixels)
{
    const ImageHeader& h = decoded.header;
    const std::size_t count = std::size_t(h.width) * h.height;
    for (std::size_t i = 0; i < count; ++i)
        for (int c = 0; c < channels; ++c) {
            const std::size_t at = i * h.channels + c;
            // OIIO's conversion: v · (1/max), not v / max (they differ in the last bit).
            pixels[i * channels + c] =
                h.sample == Sample::u16
                    ? float(reinterpret_cast<const std::uint16_t*>(decoded.rows.data())[at]) * (1.0f / 65535.0f)
                    : float(decoded.rows[at]) * (1.0f / 255.0f);
        }
}

class PngReader final : public ImageReader {
public:
    PngReader(std::unique_ptr<std::FILE, int (*)(std::FILE*)> file, Decoded decoded)
        : file_(std::move(file)), decoded_(std::move(decoded))
    {
    }
    const ImageHeader& header() const override { return decoded_.header; }
    std::string read(int channels, float* pixels) override
    {
        std::rewind(file_.get());
        Source source;
        source.file = file_.get();
        PngErrors errors;
        if (!decode(source, true, decoded_, errors)) return errors.message;
        to_float(decoded_, std::min(channels, decoded_.header.channels), pixels);
        return {};
    }

private:
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
    Decoded decoded_;
};

/// The string attributes as uncompressed tEXt chunks (pointing into `header`).
std::vector<png_text> text_chunks(const ImageHeader& header)
{
    std::vector<png_text> texts;
    texts.reserve(header.attributes.size());
    for (const auto& [name, value] : header.attributes) {
        png_text text{};
        text.compression = PNG_TEXT_COMPRESSION_NONE;
        text.key = const_cast<char*>(name.c_str());
        text.text = const_cast<char*>(value.c_str());
        texts.push_back(text);
    }
    return texts;
}

/// libpng's calls of encode(), after its setjmp. Kept out of line: what the compiler inlines into
/// the function that calls setjmp may sit in registers that the longjmp restores stale (g++ 16
/// warned -Wclobbered of std::vector's growth here). A longjmp leaves this frame without
/// unwinding it, so it creates nothing that needs destroying.
[[gnu::noinline]] void write_png(png_structp png, png_infop info, Sink& sink, const ImageHeader& header,
                                 std::vector<png_text>& texts, const std::uint8_t* rows, std::size_t stride, int level)
{
    png_set_write_fn(png, &sink, &Sink::write, &Sink::flush);
    png_set_compression_level(png, level);
    // OIIO sets zlib's default strategy (libpng's own default with row filters is Z_FILTERED).
    png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
    const int colour = header.channels == 1 ? PNG_COLOR_TYPE_GRAY : header.channels == 3 ? PNG_COLOR_TYPE_RGB : -1;
    if (colour < 0) png_error(png, "the built-in PNG writer takes grey or RGB");
    png_set_IHDR(png, info, png_uint_32(header.width), png_uint_32(header.height), header.sample == Sample::u16 ? 16 : 8,
                 colour, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_oFFs(png, info, 0, 0, PNG_OFFSET_PIXEL);
    for (const auto& [name, value] : header.attributes)
        if (name == "oiio:ColorSpace" && value == "sRGB") png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
    if (!texts.empty()) png_set_text(png, info, texts.data(), int(texts.size()));
    png_write_info(png, info);
    if (header.sample == Sample::u16) png_set_swap(png);
    for (int y = 0; y < header.height; ++y) png_write_row(png, const_cast<png_bytep>(rows + std::size_t(y) * stride));
    png_write_end(png, info);
}

/// OIIO 2.4's PNG writer's chunks: IHDR; gAMA, sRGB and cHRM when the colour space is sRGB;
/// oFFs (0, 0); the string attributes as tEXt ("oiio:ColorSpace" included); the rows; the end.
std::string encode(Sink& sink, const ImageHeader& header, const std::uint8_t* rows, std::size_t stride, int level)
{
    PngErrors errors;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, &PngErrors::error, &PngErrors::warning);
    if (!png) return "out of memory";
    png_infop info = png_create_info_struct(png);
    struct Destroy {
        png_structp* png;
        png_infop* info;
        ~Destroy() { png_destroy_write_struct(png, info); }
    } destroy{&png, &info};
    if (!info) return "out of memory";
    // Every C++ object the longjmp below may skip is built before the setjmp.
    std::vector<png_text> texts = text_chunks(header);
    if (setjmp(png_jmpbuf(png))) return errors.message.empty() ? std::string("PNG encoding failed") : errors.message;
    write_png(png, info, sink, header, texts, rows, stride, level);
    return {};
}

/// OIIO's float → integer conversion: clamp to [0, 1], v · max + 0.5, truncated.
template <class T>
std::vector<std::uint8_t> quantise_rows(const ImageHeader& header, const float* pixels)
{
    const std::size_t count = std::size_t(header.width) * header.height * header.channels;
    std::vector<std::uint8_t> bytes(count * sizeof(T));
    const float max = float(T(~T(0)));
    for (std::size_t i = 0; i < count; ++i) {
        const T value = T(std::clamp(pixels[i], 0.0f, 1.0f) * max + 0.5f);
        std::memcpy(&bytes[i * sizeof(T)], &value, sizeof(T));
    }
    return bytes;
}

class PngCodec final : public ImageCodec {
public:
    const char* name() const override { return "PNG"; }

    std::unique_ptr<ImageReader> open(const std::string& path, bool, std::string& error) override
    {
        std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
        if (!file) return error = std::strerror(errno), nullptr;
        Source source;
        source.file = file.get();
        Decoded decoded;
        PngErrors errors;
        if (!decode(source, false, decoded, errors)) return error = errors.message, nullptr;
        if (decoded.declined) return nullptr;
        return std::make_unique<PngReader>(std::move(file), std::move(decoded));
    }

    bool writes(const std::string& path, bool tiled_mip, std::string& format) override
    {
        if (!has_extension(path, ".png")) return false;
        format = "png";
        return !tiled_mip;
    }

    std::string write(const std::string&, const std::string& target, const ImageHeader& header, const float* pixels) override
    {
        if (header.sample != Sample::u8 && header.sample != Sample::u16) return "the built-in PNG writer takes 8 or 16 bits";
        const std::vector<std::uint8_t> rows = header.sample == Sample::u16 ? quantise_rows<std::uint16_t>(header, pixels)
                                                                            : quantise_rows<std::uint8_t>(header, pixels);
        std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(target.c_str(), "wb"), &std::fclose);
        if (!file) return std::strerror(errno);
        Sink sink;
        sink.file = file.get();
        const std::size_t stride = std::size_t(header.width) * header.channels * (header.sample == Sample::u16 ? 2 : 1);
        // OIIO's default level (pngoutput.cpp): 6.
        std::string error = encode(sink, header, rows.data(), stride, 6);
        if (!error.empty()) return error;
        const bool failed = std::fflush(file.get()) != 0 || std::ferror(file.get());
        const std::string reason = std::strerror(errno);
        if (std::fclose(file.release()) != 0 || failed) return reason;
        return {};
    }

    std::string write_mip(const std::string&, const std::string&, const MipSource&) override
    {
        return "PNG cannot hold a tiled, MIP-mapped image";
    }

    bool convert_colour(float*, std::size_t, int, const std::string&, const std::string&, std::string& error) override
    {
        error = "the PNG codec converts no colours";
        return false;
    }
};

}  // namespace

ImageCodec& png_codec()
{
    static PngCodec codec;
    return codec;
}

std::vector<std::uint8_t> encode_grey_png(int width, int height, int bits, const std::uint16_t* samples)
{
    ImageHeader header;
    header.width = width, header.height = height, header.channels = 1;
    header.sample = bits == 16 ? Sample::u16 : Sample::u8;
    std::vector<std::uint8_t> rows(std::size_t(width) * height * (bits == 16 ? 2 : 1));
    for (std::size_t i = 0; i < std::size_t(width) * height; ++i) {
        if (bits == 16)
            std::memcpy(&rows[2 * i], &samples[i], 2);
        else
            rows[i] = std::uint8_t(samples[i]);
    }
    std::vector<std::uint8_t> bytes;
    Sink sink;
    sink.bytes = &bytes;
    // Level 9, fixed: the same image always encodes to the same bytes (canonical .stex files).
    const std::string error = encode(sink, header, rows.data(), std::size_t(width) * (bits == 16 ? 2 : 1), 9);
    if (!error.empty()) throw std::runtime_error("cannot encode PNG: " + error);
    return bytes;
}

std::string decode_grey_png(const std::vector<std::uint8_t>& png, int& width, int& height, int& channels, int& bits,
                            std::vector<std::uint16_t>* samples)
{
    Source source;
    source.data = png.data();
    source.size = png.size();
    Decoded decoded;
    PngErrors errors;
    // The planes are data: any colour chunk is irrelevant, so nothing is declined here.
    if (!decode(source, false, decoded, errors, false)) return "unreadable PNG: " + errors.message;
    width = decoded.header.width, height = decoded.header.height, channels = decoded.header.channels;
    bits = decoded.header.sample == Sample::u16 ? 16 : 8;
    if (!samples) return {};
    if (channels != 1) return "not a grey PNG";
    source.at = 0;
    if (!decode(source, true, decoded, errors, false)) return "truncated or corrupt PNG: " + errors.message;
    samples->resize(std::size_t(width) * height);
    for (std::size_t i = 0; i < samples->size(); ++i) {
        if (bits == 16)
            std::memcpy(&(*samples)[i], &decoded.rows[2 * i], 2);
        else
            (*samples)[i] = decoded.rows[i];
    }
    return {};
}

}  // namespace stochtex::codec
