// Normal and albedo maps from a PTM, for renderers without PTM support.
//
// Lambertian estimator: the least-squares fit of g·l, l = (l_u, l_v, √(1 − l_u² − l_v²)), to the
// texel's PTM p over the unit disk of light projections. On the disk l_u, l_v and √(1 − r²) are
// mutually orthogonal and orthogonal to every other monomial but their own, so in the monomial
// coefficients a0 … a5 (paper eq. 8)
//   g_x = a3,  g_y = a4,  g_z = ⟨p, √(1−r²)⟩ / ‖√(1−r²)‖² = 4/3 a5 + 4/15 (a0 + a1)
// (⟨1, √(1−r²)⟩ = 2π/3, ⟨l_u², √(1−r²)⟩ = 2π/15, ‖√(1−r²)‖² = π/2). n = g/|g|, albedo = |g|.
// Maximum estimator (Malzbender et al. 2001): n's projection is where ∂p/∂l_u = ∂p/∂l_v = 0.
#include <stochtex/error.h>
#include <stochtex/models/ptm.h>

#include "models/ptm/legendre_basis.h"
#include "models/ptm/ptm_functions.h"
#include "image/image_output.h"


#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {


Vec3 lambertian_vector(const legendre::Terms& b)
{
    const legendre::Terms a = legendre::to_monomial(b);
    return {a[3], a[4], 4.0 / 3 * a[5] + 4.0 / 15 * (a[0] + a[1])};
}

Vec3 normalised(const Vec3& v)
{
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return length > 0 ? Vec3{v[0] / length, v[1] / length, v[2] / length} : Vec3{0, 0, 1};
}

/// The light projection maximising the biquadratic, if it has an interior maximum.
bool ptm_maximum(const legendre::Terms& b, Vec3& normal)
{
    const legendre::Terms a = legendre::to_monomial(b);
    const double determinant = 4 * a[0] * a[1] - a[2] * a[2];
    if (!(a[0] < 0 && determinant > 0)) return false;  // not concave: no maximum
    double lu = (a[2] * a[4] - 2 * a[1] * a[3]) / determinant;
    double lv = (a[2] * a[3] - 2 * a[0] * a[4]) / determinant;
    const double radius = std::hypot(lu, lv);
    if (radius >= 1) return false;  // the maximum lies beyond any light direction
    normal = {lu, lv, std::sqrt(1 - radius * radius)};
    return true;
}

}  // namespace

const char* to_string(NormalEstimator estimator)
{
    return estimator == NormalEstimator::lambertian ? "lambertian" : "ptm-maximum";
}

NormalEstimator normal_estimator_from_string(const std::string& name)
{
    for (NormalEstimator estimator : {NormalEstimator::lambertian, NormalEstimator::ptm_maximum})
        if (name == to_string(estimator)) return estimator;
    throw Error("unknown normal estimator '" + name + "' (valid: lambertian, ptm-maximum)");
}

SurfaceMaps estimate_surface_maps(const PtmMaps& maps, NormalEstimator estimator)
{
    const int channels = maps.coefficients.channels;
    if (channels != ptm_channel_count(maps.colour)) throw Error("surface maps: the maps have the wrong channel count");
    SurfaceMaps result{Image(maps.width(), maps.height(), 3), Image(maps.width(), maps.height(), 3)};
    for (std::size_t i = 0; i < result.normals.pixel_count(); ++i) {
        const auto functions = texel_colour_functions(maps.colour, &maps.coefficients.pixels[i * channels]);
        legendre::Terms luminance{};
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < legendre::term_count; ++k) luminance[k] += luma_weights[c] * functions[c][k];
        Vec3 normal = normalised(lambertian_vector(luminance));
        if (estimator == NormalEstimator::ptm_maximum) ptm_maximum(luminance, normal);
        for (int c = 0; c < 3; ++c) {
            const Vec3 g = lambertian_vector(functions[c]);
            result.normals.pixels[i * 3 + c] = float(normal[c]);
            result.albedo.pixels[i * 3 + c] = float(std::max(0.0, g[0] * normal[0] + g[1] * normal[1] + g[2] * normal[2]));
        }
    }
    return result;
}

void write_normal_map(const std::string& path, const Image& normals)
{
    if (normals.channels != 3 || normals.empty()) throw Error(path + ": a normal map needs 3 channels");
    std::string format;
    image_writer(path, "the normal map", false, &format);
    const bool is_float = format == "openexr";
    codec::ImageHeader spec;
    spec.width = normals.width, spec.height = normals.height, spec.channels = 3;
    spec.sample = is_float ? codec::Sample::f32 : codec::Sample::u8;
    spec.set("Software", "stochtex " STOCHTEX_VERSION);
    spec.set("ImageDescription", "tangent-space normal map: 0.5 + 0.5 n, x right, y up (data, not colour)");
    std::vector<float> encoded(normals.pixels.size());
    for (std::size_t i = 0; i < encoded.size(); ++i) encoded[i] = std::clamp(0.5f + 0.5f * normals.pixels[i], 0.0f, 1.0f);
    write_image_file(path, spec, encoded.data(), "the normal map");
}

}  // namespace stochtex
