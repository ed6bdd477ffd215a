#include "models/tiling/tiling_texture.h"

#include "models/tiling/normal_map_filter.h"
#include "schema/quantised_image.h"
#include "numerics/random.h"

#include <stochtex/error.h>
#include <stochtex/models/tiling_parameters.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stochtex {

namespace {

double srgb_to_linear(double v)
{
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

ColourMapFilter make_colour_map(const QuantisedImage& map)
{
    std::vector<float> rgb(std::size_t(map.width) * map.height * 3);
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[(std::size_t(y) * map.width + x) * 3 + c] = float(srgb_to_linear(map.value(c, x, y)));
    return ColourMapFilter(rgb, map.width);
}

}  // namespace

std::shared_ptr<const MomentPyramid> tiling_pyramid(const TilingParameters& parameters)
{
    const QuantisedImage& e = parameters.exemplar;
    return std::make_shared<const MomentPyramid>(dequantise(e), e.width, e.height);
}

TilingFilterOptions filter_options(const TilingParameters& parameters)
{
    TilingFilterOptions options;
    options.sampling.taps = parameters.filter_taps;
    return options;
}

TilingTexture::TilingTexture(const TextureDescription& description)
    : TilingTexture(description, nullptr, filter_options(description.parameters.get<TilingParameters>()))
{
}

TilingTexture::TilingTexture(const TextureDescription& description, const TilingFilterOptions& options)
    : TilingTexture(description, nullptr, options)
{
}

TilingTexture::TilingTexture(const TextureDescription& description, const Vec2& period)
    : TilingTexture(description, &period, filter_options(description.parameters.get<TilingParameters>()))
{
}

TilingTexture::TilingTexture(const TextureDescription& description, const Vec2* period, const TilingFilterOptions& options)
    : Texture(description), options_(options), output_(description.parameters.get<TilingParameters>().output)
{
    const TilingParameters& parameters = description.parameters.get<TilingParameters>();
    const std::shared_ptr<const MomentPyramid> pyramid = tiling_pyramid(parameters);
    const double edge = parameters.triangle_edge * std::min(pyramid->width(), pyramid->height());
    for (std::uint32_t plane = 0; plane < 3; ++plane) {
        // Plane 0 keeps the description's seed; the solid blend's other planes get their own.
        const std::uint32_t seed = plane == 0 ? description.seed : std::uint32_t(mix_seed(description.seed, plane, 0x7431));
        if (plane == 0 && period)
            planes_.emplace_back(pyramid, TilingGrid(seed, edge,
                                                     {(*period)[0] * description.pixels_per_unit,
                                                      (*period)[1] * description.pixels_per_unit},
                                                     parameters.blend_contrast));
        else
            planes_.emplace_back(pyramid, TilingGrid(seed, edge, parameters.blend_contrast));
    }
    packed_ = std::make_shared<const PackedMomentPyramid>(*pyramid);
    for (const TilingNoise& plane : planes_) rasters_.emplace_back(plane, *packed_);
    // The exemplar stores each channel in its map's input units (fit_tiling_exemplar): unit σ_M.
    if (output_ == TilingOutput::colour)
        colour_mapping_ = std::make_shared<const TabulatedColourMapping>(description, std::array<double, 3>{1, 1, 1});
    if (output_ == TilingOutput::colour_map) colour_map_.emplace(make_colour_map(parameters.colour_map));
}

Moments TilingTexture::moments(const Vec2& uv, const Footprint2D& f) const
{
    const double ppu = description().pixels_per_unit;
    return planes_[0].footprint_estimate(uv[0] * ppu, uv[1] * ppu, f.scaled(ppu),
                                         options_.sampling);
}

TilingTexture::PlaneCache& TilingTexture::single_cache(int k)
{
    // One per thread and plane, its buffers kept between point evaluations (no allocation per
    // eval()); the translations are forgotten each time, since another texture may have used it.
    thread_local std::array<PlaneCache, 3> caches{PlaneCache(true), PlaneCache(true), PlaneCache(true)};
    PlaneCache& cache = caches[std::size_t(k)];
    cache.workspace.invalidate();
    cache.tiles = TileCache();
    return cache;
}

Moments TilingTexture::plane_moments(int k, double x, double y, const TilingRaster::Plan& plan, PlaneCache& cache) const
{
    Moments m;
    plane_row(k, &x, 1, y, plan, cache, &m);
    return m;
}

void TilingTexture::plane_row(int k, const double* x, std::size_t count, double y, const TilingRaster::Plan& plan, PlaneCache& cache,
                              Moments* out) const
{
    const TilingRaster& raster = rasters_[std::size_t(k)];
    if (!TilingRaster::serves(plan)) {
        for (std::size_t i = 0; i < count; ++i) out[i] = planes_[std::size_t(k)].footprint_estimate(x[i], y, plan.taps, cache.tiles);
        return;
    }
    cache.packed.resize(count * PackedMomentPyramid::record);
    raster.estimate_row(x, count, y, plan, cache.workspace, cache.packed.data());
    for (std::size_t i = 0; i < count; ++i) out[i] = raster.unpack(cache.packed.data() + i * PackedMomentPyramid::record);
}

Moments TilingTexture::raster_moments(const Vec2& uv, const Footprint2D& f) const
{
    const double ppu = description().pixels_per_unit;
    PlaneCache& cache = single_cache(0);
    return plane_moments(0, uv[0] * ppu, uv[1] * ppu, rasters_[0].plan(f.scaled(ppu), options_.sampling), cache);
}

Rgb TilingTexture::colour(const Moments& m) const
{
    switch (output_) {
    case TilingOutput::colour: {
        std::array<double, 3> spread{};
        for (int c = 0; c < 3; ++c) spread[c] = std::sqrt(std::max(0.0, m.moment(c, c)));
        return colour_mapping_->to_rgb({m.mean[0], m.mean[1], m.mean[2]}, spread);
    }
    case TilingOutput::colour_map:
        return colour_map_->lookup(m.mean[0], m.mean[1], {m.moment(0, 0), m.moment(0, 1), m.moment(1, 1)},
                                     options_.colour_map);
    case TilingOutput::normal_map: {
        const Direction n = normal_from_slopes(m.mean[0], m.mean[1]);
        return {float(0.5 + 0.5 * n[0]), float(0.5 + 0.5 * n[1]), float(0.5 + 0.5 * n[2])};
    }
    }
    throw Error("tiling texture: unknown output");
}

Rgb TilingTexture::mean() const
{
    const Moments m = planes_[0].global();
    if (output_ == TilingOutput::colour_map)
        return colour_map_->filtered(m.mean[0], m.mean[1], {m.moment(0, 0), m.moment(0, 1), m.moment(1, 1)}, options_.colour_map);
    return colour(m);
}

Rgb TilingTexture::eval(const Vec2& uv, const Footprint2D& footprint) const { return colour(raster_moments(uv, footprint)); }

void TilingTexture::eval_region(const RasterRegion& region, const RgbOutput& out) const
{
    // raster_moments() at every pixel with the footprint's taps planned once and the grid's
    // vertices shared along the rows.
    const double ppu = description().pixels_per_unit;
    const TilingRaster::Plan plan = rasters_[0].plan(region.footprint.scaled(ppu), options_.sampling);
    PlaneCache cache;
    std::vector<double> x(std::size_t(region.width));
    for (int i = 0; i < region.width; ++i) x[std::size_t(i)] = region.u(i) * ppu;
    if (TilingRaster::serves(plan)) {
        cache.packed.resize(x.size() * PackedMomentPyramid::record);
        for (int j = 0; j < region.height; ++j) {
            rasters_[0].estimate_row(x.data(), x.size(), region.v(j) * ppu, plan, cache.workspace, cache.packed.data());
            colour_row(cache.packed.data(), x.size(), out, std::size_t(j) * region.width, cache);
        }
        return;
    }
    std::vector<Moments> row(std::size_t(region.width));
    for (int j = 0; j < region.height; ++j) {
        plane_row(0, x.data(), x.size(), region.v(j) * ppu, plan, cache, row.data());
        for (int i = 0; i < region.width; ++i) out.set(std::size_t(j) * region.width + i, colour(row[std::size_t(i)]));
    }
}

void TilingTexture::colour_row(const float* packed, std::size_t count, const RgbOutput& out, std::size_t first, PlaneCache& cache) const
{
    constexpr int record = PackedMomentPyramid::record;
    if (output_ == TilingOutput::colour_map) {
        // colour(unpack(record)) without the double Moments: the means made absolute as unpack()
        // makes them, the three second moments read from their record lanes (packed_pairs(2)).
        const PackedPairs pairs = packed_pairs(2);
        int lane[2][2] = {};
        for (int p = 0; p < pairs.count; ++p)
            lane[pairs.first[std::size_t(p)]][pairs.second[std::size_t(p)]] = lane[pairs.second[std::size_t(p)]][pairs.first[std::size_t(p)]] =
                2 + p;
        const Moments& global = planes_[0].global();
        cache.channels.resize(2 * count);
        cache.covariance.resize(count);
        cache.colours.resize(count);
        double* a = cache.channels.data(), * b = a + count;
        for (std::size_t i = 0; i < count; ++i) {
            const float* r = packed + i * record;
            a[i] = global.mean[0] + double(r[0]), b[i] = global.mean[1] + double(r[1]);
            cache.covariance[i] = {double(r[lane[0][0]]), double(r[lane[0][1]]), double(r[lane[1][1]])};
        }
        colour_map_->lookup_row(count, a, b, cache.covariance.data(), options_.colour_map, cache.colours.data());
        for (std::size_t i = 0; i < count; ++i) out.set(first + i, cache.colours[i]);
        return;
    }
    if (output_ != TilingOutput::colour) {
        for (std::size_t i = 0; i < count; ++i) out.set(first + i, colour(rasters_[0].unpack(packed + i * record)));
        return;
    }
    // unpack()'s means and colour()'s spreads, planar: record lanes 0–2 the centred means, 3–5
    // the variances (packed_pairs(3)).
    const Moments& global = planes_[0].global();
    cache.channels.resize(6 * count);
    std::array<double*, 3> z{}, spread{};
    for (int c = 0; c < 3; ++c) z[c] = cache.channels.data() + std::size_t(c) * count, spread[c] = z[c] + 3 * count;
    tiling_raster::colour_inputs(packed, count, global.mean.data(), z.data(), spread.data());
    colour_mapping_->to_rgb({z[0], z[1], z[2]}, {spread[0], spread[1], spread[2]}, count, out, first);
}

TilingTexture::SolidPlan TilingTexture::solid_plan(const SurfacePoint& point) const
{
    // Plane k spans the axes (k, k+1 mod 3) and faces axis k+2: weights ∝ n⁴, Σ ω² = 1.
    const double ppu = description().pixels_per_unit;
    const double length = std::sqrt(point.n[0] * point.n[0] + point.n[1] * point.n[1] + point.n[2] * point.n[2]);
    std::array<double, 3> omega{};
    double norm = 0;
    for (int k = 0; k < 3; ++k) {
        const double facing = length > 0 ? point.n[(k + 2) % 3] / length : (k == 0 ? 1.0 : 0.0);
        omega[k] = std::pow(facing, 4);
        norm += omega[k] * omega[k];
    }
    SolidPlan plan;
    for (int k = 0; k < 3; ++k) {
        plan.weight[k] = omega[k] / std::sqrt(norm);
        if (plan.weight[k] == 0) continue;
        const int s = k, t = (k + 1) % 3;
        // The footprint projected on the plane (s, t), in exemplar pixels.
        const Footprint2D footprint = Footprint2D{point.dpdx[s], point.dpdx[t], point.dpdy[s], point.dpdy[t]}.scaled(ppu);
        plan.taps[k] = rasters_[k].plan(footprint, options_.sampling);
    }
    return plan;
}

Moments TilingTexture::solid_moments(const SolidPlan& plan, const std::array<Moments, 3>& planes) const
{
    const Moments& global = planes_[0].global();
    Moments result;
    result.channels = global.channels;
    result.mean = global.mean;
    for (int k = 0; k < 3; ++k) {
        const double w = plan.weight[k];
        if (w == 0) continue;
        const Moments& m = planes[std::size_t(k)];
        for (int a = 0; a < result.channels; ++a) {
            result.mean[a] += w * (m.mean[a] - global.mean[a]);
            for (int b = 0; b < result.channels; ++b) result.moment(a, b) += w * w * m.moment(a, b);
        }
    }
    return result;
}

Rgb TilingTexture::eval_solid(const SurfacePoint& point) const
{
    const double ppu = description().pixels_per_unit;
    const SolidPlan plan = solid_plan(point);
    std::array<Moments, 3> planes;
    for (int k = 0; k < 3; ++k) {
        if (plan.weight[std::size_t(k)] == 0) continue;
        planes[std::size_t(k)] = plane_moments(k, point.p[std::size_t(k)] * ppu, point.p[std::size_t((k + 1) % 3)] * ppu,
                                               plan.taps[std::size_t(k)], single_cache(k));
    }
    return colour(solid_moments(plan, planes));
}

void TilingTexture::eval_solid_region(const SolidRegion& region, const RgbOutput& out) const
{
    // One normal (+w) and one footprint for the whole slice: one plan, vertices shared.
    const RasterRegion& plane = region.plane;
    SurfacePoint point;
    point.dpdx = {plane.footprint.dudx, plane.footprint.dvdx, 0};
    point.dpdy = {plane.footprint.dudy, plane.footprint.dvdy, 0};
    const SolidPlan plan = solid_plan(point);
    const double ppu = description().pixels_per_unit;
    std::array<PlaneCache, 3> caches;
    std::array<std::vector<Moments>, 3> rows;
    std::vector<double> u(std::size_t(plane.width));
    for (int i = 0; i < plane.width; ++i) u[std::size_t(i)] = plane.u(i) * ppu;
    for (int j = 0; j < plane.height; ++j) {
        // Plane k reads (p_k, p_(k+1)): planes 0 (u, v) and 1 (v, w) are rows of constant
        // second coordinate; plane 2 (w, u) is not, and goes point by point.
        const double v = plane.v(j) * ppu, w = region.w * ppu;
        for (int k = 0; k < 3; ++k) {
            if (plan.weight[std::size_t(k)] == 0) continue;
            std::vector<Moments>& row = rows[std::size_t(k)];
            row.resize(u.size());
            if (k == 0) plane_row(0, u.data(), u.size(), v, plan.taps[0], caches[0], row.data());
            if (k == 1) {
                caches[1].x.assign(u.size(), v);
                plane_row(1, caches[1].x.data(), u.size(), w, plan.taps[1], caches[1], row.data());
            }
            if (k == 2)
                for (std::size_t i = 0; i < u.size(); ++i) plane_row(2, &w, 1, u[i], plan.taps[2], caches[2], &row[i]);
        }
        std::array<Moments, 3> planes;
        for (int i = 0; i < plane.width; ++i) {
            for (int k = 0; k < 3; ++k)
                if (plan.weight[std::size_t(k)] != 0) planes[std::size_t(k)] = rows[std::size_t(k)][std::size_t(i)];
            out.set(std::size_t(j) * plane.width + i, colour(solid_moments(plan, planes)));
        }
    }
}

}  // namespace stochtex

namespace stochtex {

std::string describe_tiling(const TextureDescription& d)
{
    const TilingParameters& t = d.parameters.get<TilingParameters>();
    const QuantisedImage& e = t.exemplar;
    const std::shared_ptr<const MomentPyramid> pyramid = tiling_pyramid(t);
    const Moments global = pyramid->global();
    const int side = std::min(e.width, e.height);
    char line[256];
    std::string out;
    auto add = [&](const char* text) { out += text; };
    std::snprintf(line, sizeof line, "tiling       output %s; exemplar %dx%d, %d channels, %d bits (%.4g x %.4g texture units)\n",
                  to_string(t.output), e.width, e.height, e.channels, e.bits, e.width / d.pixels_per_unit,
                  e.height / d.pixels_per_unit);
    add(line);
    const double edge_px = t.triangle_edge * side;
    std::snprintf(line, sizeof line,
                  "grid         triangle edge %.4g exemplar widths = %.1f px; hexagonal tiles %.1f px across; %d pyramid levels\n",
                  t.triangle_edge, edge_px, 2 * edge_px, pyramid->level_count());
    add(line);
    if (t.blend_contrast != 1) {
        std::snprintf(line, sizeof line, "blend        contrast %.4g (weights B^%.4g, normalised to sum of squares 1)\n",
                      t.blend_contrast, t.blend_contrast);
        add(line);
    }
    for (int c = 0; c < e.channels; ++c) {
        std::snprintf(line, sizeof line, "channel %d    mean %+.5f, sigma %.5f (exact, exemplar), stored range [%.4g, %.4g]\n", c,
                      global.mean[c], std::sqrt(global.moment(c, c)), e.ranges[c][0], e.ranges[c][1]);
        add(line);
    }
    if (e.channels == 2) {
        const double r = global.moment(0, 1) / std::sqrt(global.moment(0, 0) * global.moment(1, 1));
        std::snprintf(line, sizeof line, "correlation  %+.4f between the two channels\n", r);
        add(line);
    }
    if (t.output == TilingOutput::colour_map) {
        std::snprintf(line, sizeof line, "colour map   %dx%d sRGB, %d bits\n", t.colour_map.width, t.colour_map.height, t.colour_map.bits);
        add(line);
    }
    return out;
}

}  // namespace stochtex
