#include "models/ptm/ptm_texture.h"

#include "models/ptm/ptm_functions.h"
#include "numerics/exact_rounding.h"

#include <stochtex/error.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/ptm_parameters.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stochtex {

namespace {
int wrap(long long i, int n) { return int(((i % n) + n) % n); }
}  // namespace

std::string describe_ptm(const TextureDescription& description)
{
    const PtmParameters& ptm = description.parameters.get<PtmParameters>();
    char text[512];
    std::snprintf(text, sizeof text,
                  "ptm          %s, %dx%d texels of Legendre coefficients in %s\n"
                  "light        (%.4f, %.4f, %.4f)  (x right, y up, z out; hint stex:light)\n",
                  to_string(ptm.colour), ptm.maps->width(), ptm.maps->height(),
                  ptm.coefficient_file.empty() ? "(not written yet)" : ptm.coefficient_file.c_str(), ptm.light[0],
                  ptm.light[1], ptm.light[2]);
    std::string out = text;
    if (ptm.unbounded) {
        std::snprintf(text, sizeof text,
                      "unbounded    tiled and blended: triangle edge %.4g maps widths = %.1f texels, seed %u\n",
                      ptm.triangle_edge, ptm.triangle_edge * std::min(ptm.maps->width(), ptm.maps->height()),
                      unsigned(description.seed));
        out += text;
    }
    return out;
}

PtmTexture::PtmTexture(const TextureDescription& description) : PtmTexture(description, nullptr) {}

PtmTexture::PtmTexture(const TextureDescription& description, const Vec2& period) : PtmTexture(description, &period) {}

PtmTexture::PtmTexture(const TextureDescription& description, const Vec2* period) : Texture(description)
{
    const PtmParameters& ptm = description.parameters.get<PtmParameters>();
    const PtmMaps& maps = *ptm.maps;
    basis_ = basis_at(ptm.light);
    Level base{maps.width(), maps.height(), {}};
    base.functions.resize(std::size_t(base.width) * base.height * floats_per_texel);
    const int channels = maps.coefficients.channels;
    for (std::size_t i = 0; i < maps.coefficients.pixel_count(); ++i) {
        const auto functions = texel_colour_functions(maps.colour, &maps.coefficients.pixels[i * channels]);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < legendre::term_count; ++k)
                base.functions[i * floats_per_texel + c * legendre::term_count + k] = float(functions[c][k]);
    }
    levels_.push_back(std::move(base));
    // Box filter, 2 × 2 texels (wrapping: an odd size pairs its last texel with the first).
    while (levels_.back().width > 1 || levels_.back().height > 1) {
        const Level& fine = levels_.back();
        Level coarse{std::max(1, (fine.width + 1) / 2), std::max(1, (fine.height + 1) / 2), {}};
        coarse.functions.assign(std::size_t(coarse.width) * coarse.height * floats_per_texel, 0.0f);
        const int span_x = fine.width > 1 ? 2 : 1, span_y = fine.height > 1 ? 2 : 1;
        for (int y = 0; y < coarse.height; ++y)
            for (int x = 0; x < coarse.width; ++x) {
                double sum[floats_per_texel] = {};
                for (int j = 0; j < span_y; ++j)
                    for (int i = 0; i < span_x; ++i)
                        add_texel(fine, wrap(2 * x + i, fine.width), wrap(2 * y + j, fine.height), 1.0 / (span_x * span_y), sum);
                std::copy(sum, sum + floats_per_texel, &coarse.functions[(std::size_t(y) * coarse.width + x) * floats_per_texel]);
            }
        levels_.push_back(std::move(coarse));
    }
    const double natural[2] = {maps.width() / description.pixels_per_unit, maps.height() / description.pixels_per_unit};
    if (ptm.unbounded) {
        const double edge = ptm.triangle_edge * std::min(maps.width(), maps.height());
        if (period)
            grid_.emplace(description.seed, edge, std::array<double, 2>{(*period)[0] * description.pixels_per_unit,
                                                                         (*period)[1] * description.pixels_per_unit});
        else
            grid_.emplace(description.seed, edge);
    }
    for (int axis = 0; axis < 2; ++axis) {
        texels_per_unit_[axis] = description.pixels_per_unit;
        if (period && !grid_) {
            const double repeats = std::max(1.0, std::round((*period)[axis] / natural[axis]));
            texels_per_unit_[axis] *= repeats * natural[axis] / (*period)[axis];
        }
    }
    std::array<legendre::Terms, 3> coarsest{};
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < legendre::term_count; ++k)
            coarsest[c][k] = levels_.back().functions[c * legendre::term_count + k];
    mean_ = lit(coarsest);
}

void PtmTexture::add_texel(const Level& level, int x, int y, double weight, double* sum) const
{
    // A zero weight adds ±0 to every (finite) sum, which changes no bit: skip the texel (a raster
    // aligned with the level's texels, as every MIP level and plugin tile is, reads one of four).
    if (weight == 0) return;
    const float* texel = &level.functions[(std::size_t(y) * level.width + x) * floats_per_texel];
    for (int k = 0; k < floats_per_texel; ++k) sum[k] += weight * texel[k];
}

void PtmTexture::bilinear(const Level& level, double x, double y, double* sum, double weight) const
{
    // x, y in this level's texels with texel centres at half-integers; one floor-modulo per
    // axis, the neighbour wraps by comparison.
    const double fx = floor_exact(x - 0.5), fy = floor_exact(y - 0.5);
    const double tx = x - 0.5 - fx, ty = y - 0.5 - fy;
    const int x0 = wrap((long long)fx, level.width), y0 = wrap((long long)fy, level.height);
    const int x1 = x0 + 1 == level.width ? 0 : x0 + 1, y1 = y0 + 1 == level.height ? 0 : y0 + 1;
    add_texel(level, x0, y0, weight * (1 - tx) * (1 - ty), sum);
    add_texel(level, x1, y0, weight * tx * (1 - ty), sum);
    add_texel(level, x0, y1, weight * (1 - tx) * ty, sum);
    add_texel(level, x1, y1, weight * tx * ty, sum);
}

PtmTexture::Detail PtmTexture::detail(double footprint_units) const
{
    const double footprint = footprint_units * std::max(texels_per_unit_[0], texels_per_unit_[1]);
    const double lod = std::clamp(std::log2(std::max(footprint, 1.0)), 0.0, double(levels_.size() - 1));
    const int fine = int(lod);
    return {fine, lod - fine};
}

void PtmTexture::trilinear(double x, double y, const Detail& detail, double* sum, double weight) const
{
    for (int level = detail.fine; level <= std::min(detail.fine + 1, int(levels_.size()) - 1); ++level) {
        const double w = level == detail.fine ? 1 - detail.t : detail.t;
        if (w == 0) continue;
        const Level& l = levels_[level];
        bilinear(l, x * l.width / levels_[0].width, y * l.height / levels_[0].height, sum, weight * w);
    }
}

void PtmTexture::function_sum(const Vec2& uv, const Detail& detail, TileCache& cache, double* sum) const
{
    const double x0 = uv[0] * texels_per_unit_[0], y0 = uv[1] * texels_per_unit_[1];
    std::fill(sum, sum + floats_per_texel, 0.0);
    if (!grid_) {
        trilinear(x0, y0, detail, sum, 1);
        return;
    }
    // ν + Σ w_i (f_i − ν): the tiles' functions with the grid's weights, one set for all fields.
    const float* mean = levels_.back().functions.data();
    double weights = 0;
    for (const TileVertex& vertex : grid_->blend(x0, y0, cache)) {
        if (vertex.weight == 0) continue;
        const std::array<double, 2> t = tile_position(vertex, x0, y0, levels_[0].width, levels_[0].height);
        trilinear(t[0], t[1], detail, sum, vertex.weight);
        weights += vertex.weight;
    }
    for (int k = 0; k < floats_per_texel; ++k) sum[k] += (1 - weights) * double(mean[k]);
}

std::array<legendre::Terms, 3> PtmTexture::functions(const Vec2& uv, double footprint_units) const
{
    double sum[floats_per_texel];
    TileCache cache;
    function_sum(uv, detail(footprint_units), cache, sum);
    std::array<legendre::Terms, 3> result{};
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < legendre::term_count; ++k) result[c][k] = sum[c * legendre::term_count + k];
    return result;
}

Rgb PtmTexture::lit(const std::array<legendre::Terms, 3>& functions) const
{
    Rgb rgb{};
    for (int c = 0; c < 3; ++c) rgb[c] = float(std::max(0.0, legendre::dot(functions[c], basis_)));
    return rgb;
}

Rgb PtmTexture::lit(const double* sum) const
{
    // lit(functions) without the copies: legendre::dot's sum, k = 0 … 5, per channel.
    Rgb rgb{};
    for (int c = 0; c < 3; ++c) {
        double value = 0;
        for (int k = 0; k < legendre::term_count; ++k) value += sum[c * legendre::term_count + k] * basis_[k];
        rgb[c] = float(std::max(0.0, value));
    }
    return rgb;
}

Rgb PtmTexture::eval(const Vec2& uv, const Footprint2D& footprint) const
{
    return lit(functions(uv, footprint.major_axis()));
}

Rgb PtmTexture::eval_solid(const SurfacePoint& point) const
{
    return lit(functions({point.p[0], point.p[1]}, point.major_axis()));
}

void PtmTexture::eval_raster(const RasterRegion& region, double footprint_units, const RgbOutput& out) const
{
    const Detail d = detail(footprint_units);
    TileCache cache;
    double sum[floats_per_texel];
    for (int j = 0; j < region.height; ++j)
        for (int i = 0; i < region.width; ++i) {
            function_sum({region.u(i), region.v(j)}, d, cache, sum);
            out.set(std::size_t(j) * region.width + i, lit(sum));
        }
}

void PtmTexture::eval_region(const RasterRegion& region, const RgbOutput& out) const
{
    eval_raster(region, region.footprint.major_axis(), out);
}

void PtmTexture::eval_solid_region(const SolidRegion& region, const RgbOutput& out) const
{
    // eval_solid() projects on (u, v): the slice is the 2D raster, filtered at the footprint of
    // its surface points (normal +w) as eval_solid() measures it.
    SurfacePoint point;
    point.dpdx = {region.plane.footprint.dudx, region.plane.footprint.dvdx, 0};
    point.dpdy = {region.plane.footprint.dudy, region.plane.footprint.dvdy, 0};
    eval_raster(region.plane, point.major_axis(), out);
}

}  // namespace stochtex
