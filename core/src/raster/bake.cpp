#include <stochtex/atomic_write.h>
#include <stochtex/bake.h>
#include <stochtex/error.h>
#include <stochtex/mip_image.h>
#include <stochtex/texture.h>

#include "image/image_output.h"
#include "parallel/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace stochtex {

namespace {

/// Fills one row of tiles (tile_height rows of the level, whole width), a tile per item: each
/// tile is its own region of the level, so the strip is the same whatever the thread count.
void fill_strip(const MipImage& image, int level, int y0, int rows, int tile_width, int threads, float* strip)
{
    const int width = image.level_width(level);
    parallel_for((width + tile_width - 1) / tile_width, threads, [&](int t) {
        const int x0 = t * tile_width, w = std::min(tile_width, width - x0);
        std::vector<float> tile(std::size_t(w) * rows * 3);
        image.fill(level, x0, y0, w, rows, tile.data());
        for (int y = 0; y < rows; ++y)
            std::copy_n(&tile[std::size_t(y) * w * 3], std::size_t(w) * 3, strip + (std::size_t(y) * width + x0) * 3);
    });
}

}  // namespace

BakeSummary bake_mip_image(const TextureDescription& description, const std::string& path, const BakeOptions& options,
                           const ProgressCallback& progress)
{
    ImageLayout layout;
    layout.width = options.width;
    layout.height = options.height;
    layout.tile_width = layout.tile_height = options.tile_size;
    layout.scale = options.scale;
    layout.channels = "RGB";
    const MipImage image(description, layout, path);  // validates the description and the layout

    codec::ImageCodec& writer = image_writer(path, "the bake", true);
    check_output_path(path, "the bake");

    const int threads = thread_count(options.threads);
    double total_texels = 0;
    for (int level = 0; level < image.level_count(); ++level)
        total_texels += double(image.level_width(level)) * image.level_height(level);

    codec::MipSource source;
    source.header.width = image.level_width(0);
    source.header.height = image.level_height(0);
    source.header.channels = 3;
    source.header.sample = options.half ? codec::Sample::half : codec::Sample::f32;
    source.header.tile_size = options.tile_size;
    source.header.set("oiio:ColorSpace", "Linear");
    source.header.set("textureformat", "Plain Texture");
    source.header.set("wrapmodes", "periodic,periodic");
    source.header.set("compression", "zip");
    source.header.set("Software", "stochtex " STOCHTEX_VERSION);
    source.header.set("stochtex:source", description.provenance.source);
    source.levels = image.level_count();
    source.level_size = [&](int level) { return std::pair<int, int>(image.level_width(level), image.level_height(level)); };
    source.fill = [&](int level, int y0, int rows, float* strip) {
        fill_strip(image, level, y0, rows, options.tile_size, threads, strip);
    };
    if (progress) source.progress = [&](double done) { progress(done / total_texels, "bake"); };

    AtomicOutput file(path);  // removes its temporary on every error below
    const std::string error = writer.write_mip(path, file.temporary(), source);
    if (!error.empty()) throw Error(path + ": " + error);
    file.commit();
    return {image.level_count(), image.period()[0], image.period()[1]};
}

}  // namespace stochtex

namespace stochtex {

namespace {

struct PositionMap {
    int width = 0, height = 0;
    std::vector<float> rgba;  // raw values: positions are data, never colour-converted
    const float* at(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
    bool covered(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height && at(x, y)[3] > 0; }
};

PositionMap read_positions(const std::string& path)
{
    std::string error;
    const auto input = codec::open_image(path, error);
    if (!input) throw Error(path + ": cannot read the position map: " + error);
    const codec::ImageHeader& spec = input->header();
    if (spec.channels < 4) throw Error(path + ": a position map needs RGBA (positions and coverage)");
    PositionMap map;
    map.width = spec.width;
    map.height = spec.height;
    map.rgba.resize(std::size_t(map.width) * map.height * 4);
    error = input->read(4, map.rgba.data());
    if (!error.empty()) throw Error(path + ": cannot read the position map: " + error);
    return map;
}

/// The position derivative along one axis of the map: the shorter of the two one-sided
/// differences to covered neighbours. At an island's border (or a margin's rim) the neighbour
/// across it is another part of the surface or empty space; the shorter difference is the one
/// along the surface, so the footprint does not blow up there. Zero for a lone texel.
Vec3 derivative(const PositionMap& map, int x, int y, int dx, int dy, double scale)
{
    const float* here = map.at(x, y);
    Vec3 best{0, 0, 0};
    double best_length = -1;
    for (int side : {1, -1}) {
        if (!map.covered(x + side * dx, y + side * dy)) continue;
        const float* there = map.at(x + side * dx, y + side * dy);
        const Vec3 d{(there[0] - here[0]) * scale, (there[1] - here[1]) * scale, (there[2] - here[2]) * scale};
        const double length = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (best_length < 0 || length < best_length) best = d, best_length = length;
    }
    return best;
}

}  // namespace

BakeSummary bake_solid_map(const TextureDescription& description, const std::string& positions_path,
                           const std::string& path, double units_per_position, int threads,
                           const ProgressCallback& progress)
{
    if (!(units_per_position > 0) || !std::isfinite(units_per_position))
        throw Error("solid bake: the position scale must be positive");
    // The output is checked before the work (the bake is written at the end).
    image_writer(path, "the solid map");
    check_output_path(path, "the solid map");
    const auto texture = make_texture(description);
    const PositionMap map = read_positions(positions_path);
    // Positions come from a file: each must lie where a texture can be evaluated (texture.h),
    // checked here, before any work, so the error names the texel.
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x)
            if (map.covered(x, y))
                for (int c = 0; c < 3; ++c)
                    if (!position_in_range(map.at(x, y)[c] * units_per_position, description.pixels_per_unit))
                        check_position(map.at(x, y)[c] * units_per_position, description.pixels_per_unit,
                                       positions_path + ": texel (" + std::to_string(x) + ", " + std::to_string(y) +
                                           ") position × position scale");
    std::vector<float> out(map.rgba.size(), 0.0f);
    // A row's covered texels are one batch (an item); their values land in a planar row buffer.
    parallel_for(map.height, threads, [&](int y) {
        std::vector<SurfacePoint> points;
        std::vector<int> columns;
        for (int x = 0; x < map.width; ++x) {
            if (!map.covered(x, y)) continue;
            const float* p = map.at(x, y);
            SurfacePoint point;
            point.p = {p[0] * units_per_position, p[1] * units_per_position, p[2] * units_per_position};
            point.n = {0, 0, 0};  // the derivatives lie on the surface already
            point.dpdx = derivative(map, x, y, 1, 0, units_per_position);
            point.dpdy = derivative(map, x, y, 0, 1, units_per_position);
            points.push_back(point);
            columns.push_back(x);
        }
        const std::size_t n = points.size();
        std::vector<float> planes(3 * n);
        texture->eval_solid_points({points.data(), n}, RgbOutput::planar(planes.data(), planes.data() + n, planes.data() + 2 * n));
        for (std::size_t k = 0; k < n; ++k) {
            float* texel = &out[(std::size_t(y) * map.width + columns[k]) * 4];
            texel[0] = planes[k], texel[1] = planes[n + k], texel[2] = planes[2 * n + k], texel[3] = 1.0f;
        }
    }, {progress, "solid bake"});

    codec::ImageHeader header;
    header.width = map.width, header.height = map.height, header.channels = 4;
    header.alpha_channel = 3;
    header.set("oiio:ColorSpace", "Linear");
    header.set("compression", "zip");
    header.set("Software", "stochtex " STOCHTEX_VERSION);
    write_image_file(path, header, out.data(), "the solid map");
    return {1, 0, 0};
}

}  // namespace stochtex
