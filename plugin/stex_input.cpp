// stex.imageio.so: an OpenImageIO ImageInput that reads a .stex procedural texture as a tiled,
// MIP-mapped, float image of any resolution (docs/oiio-plugin.md).
//
// All the work is the core's MipImage: this file only maps OIIO's calls onto it. What OIIO
// requires of it, and why the code looks the way it does:
// - Tiles are requested concurrently and without a lock (ImageCache/TextureSystem threads): the
//   tile path reads only state fixed at open() (the MipImage and per-level specs) and never
//   m_spec, which seek_subimage() changes.
// - Tiles are kept in a small per-file cache (tile_cache.h) because some hosts re-read them
//   (Cycles 5.2 about 9 times each); its budget is the open hint "stex:tile_cache_mb", else
//   $STOCHTEX_TILE_CACHE_MB, else default_tile_cache_mb; 0 turns it off. Blocks of more than
//   max_cached_block_tiles tiles (whole levels: oiiotool, read_image) are made in parallel
//   bands and not kept.
// - Every problem in open() is an errorfmt() naming the file and the field or hint; open-time
//   configuration hints ("stex:width" …) override the file's "image" block.
#include "tile_cache.h"
#include "tile_stats.h"

#include <stochtex/error.h>
#include <stochtex/lighting.h>
#include <stochtex/mip_image.h>
#include <stochtex/stex_file.h>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/parallel.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <limits>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

OIIO_PLUGIN_NAMESPACE_BEGIN

// The plugin ABI is whatever the OIIO it is compiled against declares (stex_imageio_version
// below): 25 for OIIO 2.4 and 2.5, 26 for 3.0, 27 for 3.1+. The source uses only the ImageInput
// interface that 2.x and 3.x share (open with a config, spec(subimage, miplevel),
// read_native_tile/scanline), none of what 3.0 removed (the virtual read_image(TypeDesc…)
// overloads); docs/oiio-plugin.md says how to build it for the OIIO a host bundles.
static_assert(OIIO_PLUGIN_VERSION >= 22, "stex.imageio needs OIIO 2.0 or later");

namespace {

/// The open-time hints this plugin understands: "stex:" + each field of the .stex image block (as
/// the core declares it, so a field added there is a hint here), then the texture's seed and
/// light and this plugin's tile cache budget. Any other "stex:" hint is an error (a typo must not
/// silently give the default).
const std::vector<std::string>& known_hints()
{
    static const std::vector<std::string> hints = [] {
        std::vector<std::string> names;
        for (const stochtex::ParameterInfo& field : stochtex::image_layout_fields()) names.push_back("stex:" + field.key);
        for (const char* own : {"stex:seed", "stex:light", "stex:tile_cache_mb"}) names.emplace_back(own);
        return names;
    }();
    return hints;
}

/// "RGB | RGBA | Y" (a declared range of words) as "RGB, RGBA or Y".
std::string alternatives(const std::string& range)
{
    const std::vector<std::string> words = Strutil::splits(range, " | ");
    std::string text;
    for (std::size_t i = 0; i < words.size(); ++i) text += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
    return text;
}

/// The tile cache's budget per open file when neither the hint nor the environment sets one:
/// about 1 300 tiles of 64² RGB floats, more than a Cycles render keeps in flight per file.
constexpr long long default_tile_cache_mb = 64;
/// Larger blocks are whole-level reads that would only flush the cache.
constexpr long long max_cached_block_tiles = 16;

/// The whole of `text` as a number (no leading or trailing characters).
template <class Number>
bool parse_exact(const std::string& text, Number& value)
{
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    return error == std::errc() && stop == end && !text.empty();
}

/// The value of an integer hint: an int attribute, or a string holding exactly an integer.
bool integer_value(const ParamValue* p, const std::string& name, long long min, long long max, long long& value,
                   std::string& problem)
{
    long long parsed = 0;
    if (p->type() == TypeInt || p->type() == TypeUInt) {
        parsed = p->type() == TypeInt ? p->get_int() : (long long)(*(const unsigned int*)p->data());
    } else if (p->type() == TypeString) {
        if (!parse_exact(p->get_string(), parsed)) {
            problem = name + ": expected an integer, got \"" + p->get_string() + "\"";
            return false;
        }
    } else {
        problem = name + ": expected an integer, got a value of type " + p->type().c_str();
        return false;
    }
    if (parsed < min || parsed > max) {
        problem = name + ": must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                  "], got " + std::to_string(parsed);
        return false;
    }
    value = parsed;
    return true;
}

/// The integer hint `name`, if given (`value` is left alone if not).
bool integer_hint(const ImageSpec& config, const char* name, long long min, long long max, long long& value,
                  std::string& problem)
{
    const ParamValue* p = config.find_attribute(name);
    return !p || integer_value(p, name, min, max, value, problem);
}

/// The value of the hint `p` for the image-block field `field`, by the field's declared type.
/// Range checks beyond int limits are validate_image_layout's (one set of rules).
bool layout_hint_value(const ParamValue& p, const std::string& hint, const stochtex::ParameterInfo& field,
                       stochtex::ImageLayoutValue& value, std::string& problem)
{
    if (field.type == "integer") {
        long long parsed = 0;
        if (!integer_value(&p, hint, 0, std::numeric_limits<int>::max(), parsed, problem)) return false;
        value = parsed;
    } else if (field.type == "number") {
        // OIIO 2.4's get_float() gives 0 for an int (what oiiotool --iconfig makes of "-1"):
        // each type is read as itself, so that a message quotes the value given.
        if (p.type() == TypeFloat) {
            value = double(p.get_float());
        } else if (p.type() == TypeInt) {
            value = double(p.get_int());
        } else if (p.type() == TypeString) {
            double number = 0;
            if (!parse_exact(p.get_string(), number)) {
                problem = hint + ": expected a number, got \"" + p.get_string() + "\"";
                return false;
            }
            value = number;
        } else {
            problem = hint + ": expected a number, got a value of type " + p.type().c_str();
            return false;
        }
    } else {
        if (p.type() != TypeString) {
            problem = hint + ": expected a string (" + alternatives(field.range) + ")";
            return false;
        }
        value = p.get_string();
    }
    return true;
}

}  // namespace

class StexInput final : public ImageInput {
public:
    ~StexInput() override { close(); }
    const char* format_name() const override { return "stex"; }
    bool valid_file(const std::string& filename) const override;
    bool open(const std::string& name, ImageSpec& newspec) override { return open(name, newspec, ImageSpec()); }
    bool open(const std::string& name, ImageSpec& newspec, const ImageSpec& config) override;
    bool close() override;
    int current_miplevel() const override { return current_level_; }
    bool seek_subimage(int subimage, int miplevel) override;
    ImageSpec spec(int subimage, int miplevel) override;
    ImageSpec spec_dimensions(int subimage, int miplevel) override;
    bool read_native_scanline(int subimage, int miplevel, int y, int z, void* data) override;
    bool read_native_tile(int subimage, int miplevel, int x, int y, int z, void* data) override;
    bool read_native_tiles(int subimage, int miplevel, int xbegin, int xend, int ybegin, int yend, int zbegin,
                           int zend, void* data) override;

private:
    bool apply_hints(const ImageSpec& config, stochtex::TextureDescription& description,
                     stochtex::ImageLayout& layout, std::string& problem) const;
    bool tile_cache_budget(const ImageSpec& config, long long& megabytes, std::string& problem) const;
    /// The tile at (x, y) of a level, whole (texels past the level's edges zeroed), from the
    /// cache or made and kept.
    void fill_tile(int miplevel, int x, int y, float* out) const;
    bool valid_level(int subimage, int miplevel) const
    {
        return image_ && subimage == 0 && miplevel >= 0 && miplevel < image_->level_count();
    }

    std::string filename_;
    std::unique_ptr<const stochtex::MipImage> image_;
    std::vector<ImageSpec> level_specs_;  // fixed at open(): read by any thread
    std::unique_ptr<stochtex::plugin::TileCache> tiles_;  // thread-safe itself
    std::vector<stochtex::plugin::LevelTiles> level_tiles_;
    int current_level_ = 0;
};

bool StexInput::valid_file(const std::string& filename) const
{
    // A .stex file is a JSON object whose first key is "format": "stex" (the canonical writer
    // puts it first); anything else is left to other readers.
    std::ifstream in(filename, std::ios::binary);
    char head[256] = {};
    in.read(head, sizeof head - 1);
    const std::string text(head, std::size_t(in.gcount()));
    const auto brace = text.find_first_not_of(" \t\r\n");
    return brace != std::string::npos && text[brace] == '{' && text.find("\"stex\"") != std::string::npos;
}

bool StexInput::apply_hints(const ImageSpec& config, stochtex::TextureDescription& description,
                            stochtex::ImageLayout& layout, std::string& problem) const
{
    for (const ParamValue& p : config.extra_attribs) {
        const std::string name = p.name().string();
        if (!Strutil::istarts_with(name, "stex:")) continue;
        if (std::find(known_hints().begin(), known_hints().end(), name) == known_hints().end()) {
            problem = "unknown open hint \"" + name + "\" (known: " + Strutil::join(known_hints(), ", ") + ")";
            return false;
        }
    }
    for (const stochtex::ParameterInfo& field : stochtex::image_layout_fields()) {
        const std::string hint = "stex:" + field.key;
        const ParamValue* p = config.find_attribute(hint);
        if (!p) continue;
        stochtex::ImageLayoutValue value;
        if (!layout_hint_value(*p, hint, field, value, problem)) return false;
        stochtex::set_image_layout_field(layout, field.key, value, hint);
        // Checked here rather than with the rest of the layout so that the message names the
        // hint: an empty channels string is an error, not "the default" (oiiotool's --iconfig
        // with an empty value removes the hint instead, so it never gets here).
        const std::string field_problem = stochtex::image_layout_field_problem(layout, field.key);
        if (!field_problem.empty()) {
            problem = hint + " (image." + field.key + "): " + field_problem;
            return false;
        }
    }
    long long seed = description.seed;
    if (!integer_hint(config, "stex:seed", 0, 0xffffffffll, seed, problem)) return false;
    description.seed = std::uint32_t(seed);
    // The light direction of models that have one (ptm), "x,y,z" or 3 floats: the core sets it
    // and rejects models without one.
    if (const ParamValue* p = config.find_attribute("stex:light")) {
        try {
            if (p->type() == TypeString) {
                stochtex::set_light_direction(description, stochtex::parse_light_direction(p->get_string()));
            } else if (p->type().basetype == TypeDesc::FLOAT && p->type().basevalues() == 3) {
                const float* v = static_cast<const float*>(p->data());
                stochtex::set_light_direction(description, {v[0], v[1], v[2]});
            } else {
                problem = std::string("stex:light: expected \"x,y,z\" or 3 floats, got a value of type ") + p->type().c_str();
                return false;
            }
        } catch (const std::exception& e) {
            problem = std::string("stex:light: ") + e.what();
            return false;
        }
    }
    return true;
}

bool StexInput::open(const std::string& name, ImageSpec& newspec, const ImageSpec& config)
{
    close();
    try {
        stochtex::TextureDescription description = stochtex::read_stex(name);
        stochtex::ImageLayout layout = description.image.value_or(stochtex::ImageLayout{});
        std::string problem;
        if (!apply_hints(config, description, layout, problem)) {
            errorfmt("{}: {}", name, problem);
            return false;
        }
        long long cache_mb = 0;
        if (!tile_cache_budget(config, cache_mb, problem)) {
            errorfmt("{}: {}", name, problem);
            return false;
        }
        image_ = std::make_unique<const stochtex::MipImage>(description, layout, name + " (image layout and open hints)");
        tiles_ = std::make_unique<stochtex::plugin::TileCache>(std::size_t(cache_mb) << 20, image_->level_count());

        // The spec of every level is built once, here: seek_subimage() only copies one.
        ImageSpec level0(layout.width, layout.height, image_->channel_count(), TypeDesc::FLOAT);
        level0.tile_width = layout.tile_width;
        level0.tile_height = layout.tile_height;
        level0.tile_depth = 1;
        if (layout.channels == "Y") {
            level0.channelnames = {"Y"};
        } else if (layout.channels == "RGBA") {
            level0.channelnames = {"R", "G", "B", "A"};
            level0.alpha_channel = 3;
        }
        // What a texture system reads: a plain (2D) texture that wraps periodically, in linear
        // Rec.709 (the .stex colour space), with its own MIP levels.
        level0.attribute("textureformat", "Plain Texture");
        level0.attribute("wrapmodes", "periodic,periodic");
        // OIIO 2.4 knows linear data as "Linear" (without an OCIO config it does not resolve the
        // role "scene_linear"); from 2.5 on, colour spaces follow the OCIO/ACES names.
#if OIIO_VERSION >= OIIO_MAKE_VERSION(2, 5, 0)
        level0.attribute("oiio:ColorSpace", "lin_rec709");
#else
        level0.attribute("oiio:ColorSpace", "Linear");
#endif
        level0.attribute("Software", "stochtex " STOCHTEX_VERSION);
        level0.attribute("ImageDescription",
                         Strutil::fmt::format("stochtex procedural texture ({} model, seed {}), {} exemplar px per pixel",
                                              description.model, description.seed, layout.scale));
        level0.attribute("stex:model", description.model);
        level0.attribute("stex:seed", int(description.seed));
        level0.attribute("stex:scale", float(layout.scale));
        if (stochtex::depends_on_light(description)) {
            const stochtex::Vec3 light = stochtex::light_direction(description);
            level0.attribute("stex:light", Strutil::fmt::format("{},{},{}", light[0], light[1], light[2]));
        }
        for (int level = 0; level < image_->level_count(); ++level) {
            ImageSpec spec = level0;
            spec.width = spec.full_width = image_->level_width(level);
            spec.height = spec.full_height = image_->level_height(level);
            level_tiles_.push_back({(spec.width + spec.tile_width - 1) / spec.tile_width,
                                    (spec.height + spec.tile_height - 1) / spec.tile_height});
            level_specs_.push_back(std::move(spec));
        }
    } catch (const std::exception& e) {
        // stochtex errors already name the file ("x.stex: parameters.band_weights[1]: …").
        errorfmt("{}", e.what());
        close();
        return false;
    }
    filename_ = name;
    current_level_ = 0;
    m_spec = level_specs_[0];
    newspec = m_spec;
    return true;
}

bool StexInput::tile_cache_budget(const ImageSpec& config, long long& megabytes, std::string& problem) const
{
    // 2^20 MB (a terabyte) is far past any real budget; the bound keeps the byte count in range.
    constexpr long long most = 1 << 20;
    megabytes = default_tile_cache_mb;
    if (const char* env = std::getenv("STOCHTEX_TILE_CACHE_MB"); env && *env) {
        if (!parse_exact(std::string(env), megabytes) || megabytes < 0 || megabytes > most) {
            problem = "STOCHTEX_TILE_CACHE_MB: expected an integer in [0, " + std::to_string(most) + "], got \"" +
                      env + "\"";
            return false;
        }
    }
    return integer_hint(config, "stex:tile_cache_mb", 0, most, megabytes, problem);
}

bool StexInput::close()
{
    if (tiles_) stochtex::plugin::report_tile_stats(filename_, *tiles_, level_tiles_);
    tiles_.reset();
    level_tiles_.clear();
    image_.reset();
    level_specs_.clear();
    current_level_ = 0;
    return true;
}

bool StexInput::seek_subimage(int subimage, int miplevel)
{
    if (!valid_level(subimage, miplevel)) return false;
    current_level_ = miplevel;
    m_spec = level_specs_[miplevel];
    return true;
}

ImageSpec StexInput::spec(int subimage, int miplevel)
{
    if (!valid_level(subimage, miplevel)) return ImageSpec(TypeDesc::UNKNOWN);
    return level_specs_[miplevel];
}

ImageSpec StexInput::spec_dimensions(int subimage, int miplevel)
{
    if (!valid_level(subimage, miplevel)) return ImageSpec(TypeDesc::UNKNOWN);
    ImageSpec result;
    result.copy_dimensions(level_specs_[miplevel]);
    return result;
}

bool StexInput::read_native_scanline(int subimage, int miplevel, int y, int /*z*/, void* data)
{
    if (!valid_level(subimage, miplevel) || y < 0 || y >= image_->level_height(miplevel)) {
        errorfmt("{}: no scanline {} in subimage {} level {}", filename_, y, subimage, miplevel);
        return false;
    }
    image_->fill(miplevel, 0, y, image_->level_width(miplevel), 1, static_cast<float*>(data));
    return true;
}

bool StexInput::read_native_tile(int subimage, int miplevel, int x, int y, int /*z*/, void* data)
{
    if (!valid_level(subimage, miplevel)) {
        errorfmt("{}: no subimage {} level {}", filename_, subimage, miplevel);
        return false;
    }
    const ImageSpec& spec = level_specs_[miplevel];
    if (x < 0 || y < 0 || x >= spec.width || y >= spec.height || x % spec.tile_width || y % spec.tile_height) {
        errorfmt("{}: no tile at ({}, {}) in level {}", filename_, x, y, miplevel);
        return false;
    }
    fill_tile(miplevel, x, y, static_cast<float*>(data));
    return true;
}

void StexInput::fill_tile(int miplevel, int x, int y, float* out) const
{
    const ImageSpec& spec = level_specs_[miplevel];
    const int tile_w = spec.tile_width, tile_h = spec.tile_height, channels = spec.nchannels;
    const std::size_t count = std::size_t(tile_w) * tile_h * channels;
    if (tiles_->copy(miplevel, x, y, out, count)) return;
    // Tiles on the right and bottom edges hang over the level: OIIO still expects a whole
    // tile, and ignores the part outside; it is zeroed so no uninitialised memory escapes.
    const int w = std::min(tile_w, spec.width - x), h = std::min(tile_h, spec.height - y);
    if (w == tile_w && h == tile_h) {
        image_->fill(miplevel, x, y, w, h, out);
    } else {
        std::vector<float> region(std::size_t(w) * h * channels);
        image_->fill(miplevel, x, y, w, h, region.data());
        std::fill(out, out + count, 0.0f);
        for (int row = 0; row < h; ++row)
            std::copy_n(&region[std::size_t(row) * w * channels], std::size_t(w) * channels,
                        out + std::size_t(row) * tile_w * channels);
    }
    tiles_->store(miplevel, x, y, out, count);
}

bool StexInput::read_native_tiles(int subimage, int miplevel, int xbegin, int xend, int ybegin, int yend, int zbegin,
                                  int zend, void* data)
{
    // A block of whole tiles (read_image(), oiiotool, the ImageCache): rows of xend − xbegin
    // texels, where the block may hang over the level's right and bottom edges by less than a
    // tile (that part is zeroed, as in read_native_tile). The block is filled as bands of a
    // tile's rows on OIIO's thread pool (the ImageInput's threads() setting): each texel depends
    // on its own position only, so the values do not depend on the split.
    if (!valid_level(subimage, miplevel)) {
        errorfmt("{}: no subimage {} level {}", filename_, subimage, miplevel);
        return false;
    }
    const ImageSpec& spec = level_specs_[miplevel];
    const auto whole_tiles = [](int begin, int end, int size, int tile) {
        return begin >= 0 && begin < size && begin < end && begin % tile == 0 && end % tile == 0 && end - size < tile;
    };
    const auto clipped = [](int begin, int end, int size, int tile) {
        return begin >= 0 && begin % tile == 0 && begin < end && end == size;
    };
    const auto valid = [&](int begin, int end, int size, int tile) {
        return whole_tiles(begin, end, size, tile) || clipped(begin, end, size, tile);
    };
    if (!valid(xbegin, xend, spec.width, spec.tile_width) || !valid(ybegin, yend, spec.height, spec.tile_height) ||
        zbegin != 0 || zend != 1) {
        errorfmt("{}: no block of tiles [{}, {}) x [{}, {}) x [{}, {}) in level {}", filename_, xbegin, xend, ybegin,
                 yend, zbegin, zend, miplevel);
        return false;
    }
    const int stride = xend - xbegin, channels = spec.nchannels;
    const int w = std::min(xend, spec.width) - xbegin, y_stop = std::min(yend, spec.height);
    float* out = static_cast<float*>(data);
    const long long tiles_across = (stride + spec.tile_width - 1) / spec.tile_width;
    const long long tiles_down = (yend - ybegin + spec.tile_height - 1) / spec.tile_height;
    if (whole_tiles(xbegin, xend, spec.width, spec.tile_width) && whole_tiles(ybegin, yend, spec.height, spec.tile_height) &&
        tiles_across * tiles_down <= max_cached_block_tiles) {
        // Tile by tile through the cache (Cycles 5.2 reads single tiles this way), each copied
        // into its place in the block's rows.
        const std::size_t tile_row = std::size_t(spec.tile_width) * channels;
        std::vector<float> tile(tile_row * spec.tile_height);
        for (int ty = ybegin; ty < yend; ty += spec.tile_height)
            for (int tx = xbegin; tx < xend; tx += spec.tile_width) {
                fill_tile(miplevel, tx, ty, tile.data());
                for (int row = 0; row < spec.tile_height; ++row)
                    std::copy_n(&tile[row * tile_row], tile_row,
                                out + (std::size_t(ty - ybegin + row) * stride + (tx - xbegin)) * channels);
            }
        return true;
    }
    tiles_->count_made(miplevel, std::uint64_t(tiles_across * tiles_down));
    const auto row_at = [&](int64_t y) { return out + std::size_t(y - ybegin) * std::size_t(stride) * std::size_t(channels); };
    if (y_stop < yend) std::fill(row_at(y_stop), row_at(yend), 0.0f);
    const stochtex::MipImage& image = *image_;
    bool ok = true;
    std::string problem;
    std::mutex mutex;
    parallel_for_chunked(
        ybegin, y_stop, spec.tile_height,
        [&](int64_t y0, int64_t y1) {
            try {
                const int rows = int(y1 - y0);
                if (w == stride) {
                    image.fill(miplevel, xbegin, int(y0), w, rows, row_at(y0));
                    return;
                }
                std::vector<float> region(std::size_t(w) * std::size_t(rows) * std::size_t(channels));
                image.fill(miplevel, xbegin, int(y0), w, rows, region.data());
                for (int row = 0; row < rows; ++row) {
                    float* target = row_at(y0 + row);
                    std::copy_n(&region[std::size_t(row) * std::size_t(w) * std::size_t(channels)],
                                std::size_t(w) * std::size_t(channels), target);
                    std::fill(target + std::size_t(w) * std::size_t(channels),
                              target + std::size_t(stride) * std::size_t(channels), 0.0f);
                }
            } catch (const std::exception& e) {
                const std::lock_guard<std::mutex> lock(mutex);
                ok = false;
                problem = e.what();
            }
        },
        paropt(threads()));
    if (!ok) errorfmt("{}: {}", filename_, problem);
    return ok;
}

OIIO_PLUGIN_EXPORTS_BEGIN

OIIO_EXPORT int stex_imageio_version = OIIO_PLUGIN_VERSION;
OIIO_EXPORT const char* stex_imageio_library_version() { return "stochtex " STOCHTEX_VERSION; }
OIIO_EXPORT ImageInput* stex_input_imageio_create() { return new StexInput; }
OIIO_EXPORT const char* stex_input_extensions[] = {"stex", nullptr};

OIIO_PLUGIN_EXPORTS_END

OIIO_PLUGIN_NAMESPACE_END
