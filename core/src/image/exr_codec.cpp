// stochtex — the built-in OpenEXR codec (image_codec.h), the OpenEXR library directly.
//
// Reads scanline and tiled files (level 0) whose channels are half or float and either R, G, B
// (and A), or names OIIO keeps in the file's order (no R, G, B, A, Y, Z, no layers), or any
// names for a caller that finds channels by name (the ptm coefficient maps): what stochtex
// writes and the usual photo EXRs. It declines the rest (layers, luminance/chroma, subsampled,
// integer or deep channels), which OIIO then reads as before. It writes scanline
// and tiled MIP-mapped files with the header OIIO wrote for the same ImageSpec
// (tests/image_codec_test.cpp).
#include "image/image_codec.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputFile.h>

#include <algorithm>
#include <cstdint>
#include <ctime>
#include <exception>
#include <map>
#include <memory>

namespace stochtex::codec {

namespace {

/// OIIO's channel order for the R, G, B, A family: R, G, B, A (OpenEXR stores them sorted).
int rgba_rank(const std::string& name)
{
    static const char* const order[] = {"R", "G", "B", "A"};
    for (int i = 0; i < 4; ++i)
        if (name == order[i]) return i;
    return -1;
}

bool special(const std::string& name)
{
    return rgba_rank(name) >= 0 || name == "Y" || name == "Z" || name == "RY" || name == "BY" ||
           name.find('.') != std::string::npos;
}

class ExrReader final : public ImageReader {
public:
    ExrReader(std::unique_ptr<Imf::InputFile> file, ImageHeader header, std::vector<std::string> order)
        : file_(std::move(file)), header_(std::move(header)), order_(std::move(order))
    {
    }
    const ImageHeader& header() const override { return header_; }
    std::string read(int channels, float* pixels) override
    {
        try {
            const Imath::Box2i window = file_->header().dataWindow();
            const std::size_t xstride = sizeof(float) * std::size_t(channels);
            const std::size_t ystride = xstride * std::size_t(header_.width);
            // The frame buffer's origin is the data window's corner (OpenEXR addresses by
            // absolute pixel coordinates).
            char* base = reinterpret_cast<char*>(pixels) - std::ptrdiff_t(window.min.x) * std::ptrdiff_t(xstride) -
                         std::ptrdiff_t(window.min.y) * std::ptrdiff_t(ystride);
            Imf::FrameBuffer frame;
            for (int c = 0; c < channels && c < int(order_.size()); ++c)
                frame.insert(order_[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xstride, ystride));
            file_->setFrameBuffer(frame);
            file_->readPixels(window.min.y, window.max.y);
        } catch (const std::exception& e) {
            return e.what();
        }
        return {};
    }

private:
    std::unique_ptr<Imf::InputFile> file_;
    ImageHeader header_;
    std::vector<std::string> order_;
};

/// OIIO's names for what it reads into EXR header attributes (exroutput.cpp): the attributes
/// stochtex writes. Anything else is declined by the writer (the OIIO codec writes it).
bool add_attribute(Imf::Header& exr, const std::string& name, const std::string& value)
{
    if (name == "compression") {
        static const std::map<std::string, Imf::Compression> by_name{
            {"none", Imf::NO_COMPRESSION}, {"rle", Imf::RLE_COMPRESSION}, {"zips", Imf::ZIPS_COMPRESSION},
            {"zip", Imf::ZIP_COMPRESSION}, {"piz", Imf::PIZ_COMPRESSION}, {"pxr24", Imf::PXR24_COMPRESSION},
            {"b44", Imf::B44_COMPRESSION}, {"b44a", Imf::B44A_COMPRESSION}};
        const auto found = by_name.find(value);
        if (found == by_name.end()) return false;
        exr.compression() = found->second;
    } else if (name == "ImageDescription") {
        Imf::addComments(exr, value);
    } else if (name == "oiio:ColorSpace") {
        // OIIO writes no colour space into an EXR: its values are scene-linear by convention.
        return value == "Linear" || value == "linear";
    } else {
        exr.insert(name, Imf::StringAttribute(value));
    }
    return true;
}

/// The EXR header for `header` at width × height; `names` receives the channels in the
/// caller's order (the header's list is sorted by name).
std::string make_header(const ImageHeader& header, int width, int height, Imf::Header& exr, std::vector<std::string>& names)
{
    exr = Imf::Header(width, height);
    exr.compression() = Imf::ZIP_COMPRESSION;  // OIIO's default
    const Imf::PixelType type = header.sample == Sample::half ? Imf::HALF : Imf::FLOAT;
    if (header.sample != Sample::half && header.sample != Sample::f32) return "the built-in EXR writer takes half or float";
    static const char* const rgba[] = {"R", "G", "B", "A"};
    for (int c = 0; c < header.channels; ++c) {
        const std::string name = c < int(header.channel_names.size()) ? header.channel_names[c]
                                 : c < 4                                ? rgba[c]
                                                                        : "channel" + std::to_string(c);
        exr.channels().insert(name, Imf::Channel(type));
        names.push_back(name);
    }
    for (const auto& [name, value] : header.attributes)
        if (!add_attribute(exr, name, value)) return "the built-in EXR writer cannot write " + name + " = " + value;
    // OIIO stamps every file it writes with the time (DateTime → capDate): so do we.
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char date[32];
    std::strftime(date, sizeof date, "%Y:%m:%d %H:%M:%S", &local);
    Imf::addCapDate(exr, date);
    return {};
}

/// The slices of a band of rows starting at y0 (at x 0): `pixels` holds `names.size()` samples
/// of `type` (FLOAT: float, HALF: Imath::half) a texel in that order, rows of `width` texels.
/// OpenEXR addresses by absolute coordinates.
Imf::FrameBuffer frame(const std::vector<std::string>& names, const void* pixels, int width, int y0,
                       Imf::PixelType type = Imf::FLOAT)
{
    const std::size_t sample = type == Imf::HALF ? sizeof(Imath::half) : sizeof(float);
    const std::size_t xstride = sample * names.size(), ystride = xstride * std::size_t(width);
    char* base = const_cast<char*>(static_cast<const char*>(pixels)) - std::ptrdiff_t(y0) * std::ptrdiff_t(ystride);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < names.size(); ++c) frame.insert(names[c], Imf::Slice(type, base + c * sample, xstride, ystride));
    return frame;
}

class ExrCodec final : public ImageCodec {
public:
    const char* name() const override { return "OpenEXR"; }

    std::unique_ptr<ImageReader> open(const std::string& path, bool by_name, std::string& error) override
    {
        try {
            auto file = std::make_unique<Imf::InputFile>(path.c_str());
            const Imf::Header& exr = file->header();
            if (exr.hasType() && Imf::isDeepData(exr.type())) return nullptr;
            std::vector<std::string> names;
            bool any_special = false, rgb_family = true;
            for (auto c = exr.channels().begin(); c != exr.channels().end(); ++c) {
                const Imf::Channel& channel = c.channel();
                if (channel.type == Imf::UINT || channel.xSampling != 1 || channel.ySampling != 1) return nullptr;
                names.push_back(c.name());
                any_special |= special(c.name());
                rgb_family &= rgba_rank(c.name()) >= 0;
            }
            if (any_special && !rgb_family && !by_name) return nullptr;
            if (rgb_family)
                std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) { return rgba_rank(a) < rgba_rank(b); });
            ImageHeader header;
            const Imath::Box2i window = exr.dataWindow();
            // In 64 bits: a malformed header's window may not fit an int (callers then check
            // the size against their limits before reading a pixel).
            const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1,
                               height = std::int64_t(window.max.y) - window.min.y + 1;
            if (width < 1 || height < 1 || width > (1 << 30) || height > (1 << 30))
                return error = "data window of " + std::to_string(width) + "x" + std::to_string(height) + " pixels", nullptr;
            header.width = int(width);
            header.height = int(height);
            header.channels = int(names.size());
            header.channel_names = names;
            const auto alpha = std::find(names.begin(), names.end(), "A");
            header.alpha_channel = alpha == names.end() ? -1 : int(alpha - names.begin());
            header.sample = exr.channels().begin().channel().type == Imf::HALF ? Sample::half : Sample::f32;
            // OIIO names an EXR's values scene-linear unless the file says otherwise.
            const auto* colour_space = exr.findTypedAttribute<Imf::StringAttribute>("oiio:ColorSpace");
            header.set("oiio:ColorSpace", colour_space ? colour_space->value() : "Linear");
            return std::make_unique<ExrReader>(std::move(file), std::move(header), std::move(names));
        } catch (const std::exception& e) {
            error = e.what();
            return nullptr;
        }
    }

    bool writes(const std::string& path, bool, std::string& format) override
    {
        if (!has_extension(path, ".exr")) return false;
        format = "openexr";
        return true;
    }

    std::string write(const std::string&, const std::string& target, const ImageHeader& header, const float* pixels) override
    {
        Imf::Header exr;
        std::vector<std::string> names;
        if (std::string error = make_header(header, header.width, header.height, exr, names); !error.empty()) return error;
        try {
            Imf::OutputFile file(target.c_str(), exr);
            file.setFrameBuffer(frame(names, pixels, header.width, 0));
            file.writePixels(header.height);
        } catch (const std::exception& e) {
            return e.what();
        }
        return {};
    }

    std::string write_mip(const std::string&, const std::string& target, const MipSource& source) override
    {
        const ImageHeader& header = source.header;
        Imf::Header exr;
        std::vector<std::string> names;
        if (std::string error = make_header(header, header.width, header.height, exr, names); !error.empty()) return error;
        // MIPMAP_LEVELS, ROUND_DOWN: our levels, whose sizes halve as MipImage's do.
        exr.setTileDescription(Imf::TileDescription(header.tile_size, header.tile_size, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
        exr.insert("openexr:levelmode", Imf::IntAttribute(1));  // as OIIO records it
        try {
            Imf::TiledOutputFile file(target.c_str(), exr);
            if (file.numLevels() != source.levels)
                return "OpenEXR counts " + std::to_string(file.numLevels()) + " MIP levels, the image " +
                       std::to_string(source.levels);
            const int tile = header.tile_size;
            const bool half = header.sample == Sample::half;
            double done = 0;
            for (int level = 0; level < source.levels; ++level) {
                const auto [width, height] = source.level_size(level);
                if (width != file.levelWidth(level) || height != file.levelHeight(level))
                    return "MIP level " + std::to_string(level) + " is " + std::to_string(width) + "x" +
                           std::to_string(height) + ", OpenEXR expects " + std::to_string(file.levelWidth(level)) + "x" +
                           std::to_string(file.levelHeight(level));
                std::vector<float> strip(std::size_t(width) * tile * header.channels);
                // Tiled files take samples of the file's type only: half is converted here, with
                // Imath's round-to-nearest-even (OIIO's conversion).
                std::vector<Imath::half> halves(half ? strip.size() : 0);
                for (int y0 = 0, row = 0; y0 < height; y0 += tile, ++row) {
                    const int rows = std::min(tile, height - y0);
                    source.fill(level, y0, rows, strip.data());
                    if (half) std::copy(strip.begin(), strip.end(), halves.begin());
                    file.setFrameBuffer(half ? frame(names, halves.data(), width, y0, Imf::HALF)
                                             : frame(names, strip.data(), width, y0));
                    file.writeTiles(0, file.numXTiles(level) - 1, row, row, level);
                    done += double(width) * rows;
                    if (source.progress) source.progress(done);
                }
            }
        } catch (const std::exception& e) {
            return e.what();
        }
        return {};
    }

    bool convert_colour(float*, std::size_t, int, const std::string&, const std::string&, std::string& error) override
    {
        error = "the EXR codec converts no colours";
        return false;
    }

};

}  // namespace

ImageCodec& exr_codec()
{
    static ExrCodec codec;
    return codec;
}

}  // namespace stochtex::codec
