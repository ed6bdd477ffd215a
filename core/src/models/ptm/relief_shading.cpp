#include <stochtex/error.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/relief_shading.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {

int wrap(int i, int n) { return ((i % n) + n) % n; }

float height_at(const ReliefSurface& s, int x, int y) { return s.heights[std::size_t(wrap(y, s.height)) * s.width + wrap(x, s.width)]; }

/// Bilinear height at continuous texel coordinates (centres at integers).
double bilinear_height(const ReliefSurface& s, double x, double y)
{
    const double fx = std::floor(x), fy = std::floor(y);
    const int x0 = int(fx), y0 = int(fy);
    const double tx = x - fx, ty = y - fy;
    const double top = (1 - tx) * height_at(s, x0, y0) + tx * height_at(s, x0 + 1, y0);
    const double bottom = (1 - tx) * height_at(s, x0, y0 + 1) + tx * height_at(s, x0 + 1, y0 + 1);
    return (1 - ty) * top + ty * bottom;
}

Vec3 normal_at(const ReliefSurface& s, int x, int y)
{
    // y is up while rows go down: the row above (y − 1) is at +y.
    const double dhdx = 0.5 * (height_at(s, x + 1, y) - height_at(s, x - 1, y));
    const double dhdy = 0.5 * (height_at(s, x, y - 1) - height_at(s, x, y + 1));
    const double length = std::sqrt(dhdx * dhdx + dhdy * dhdy + 1);
    return {-dhdx / length, -dhdy / length, 1 / length};
}

double smoothstep(double edge0, double edge1, double x)
{
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

}  // namespace

ReliefSurface make_relief_surface(const std::string& height_map_path, int downsample, double depth)
{
    if (downsample < 1) throw Error("relief: the downsampling factor must be at least 1");
    if (!(depth > 0) || !std::isfinite(depth)) throw Error("relief: the depth must be a positive number of texels");
    ImageReadOptions data;
    data.input_colour_space = "linear";  // heights are data, whatever the file's tag says
    const Image map = read_image_linear(height_map_path, data);
    ReliefSurface surface;
    surface.width = map.width / downsample;
    surface.height = map.height / downsample;
    if (surface.width < 8 || surface.height < 8)
        throw Error(height_map_path + ": too small for a downsampling by " + std::to_string(downsample));
    surface.heights.resize(std::size_t(surface.width) * surface.height);
    surface.albedo = Image(surface.width, surface.height, 3);
    // Hollows: a dark brown; ridges: a light grey (scene-linear).
    constexpr double hollow[3] = {0.30, 0.21, 0.14}, ridge[3] = {0.62, 0.60, 0.56};
    for (int y = 0; y < surface.height; ++y)
        for (int x = 0; x < surface.width; ++x) {
            double sum = 0;
            for (int j = 0; j < downsample; ++j)
                for (int i = 0; i < downsample; ++i) sum += map.at(x * downsample + i, y * downsample + j, 0);
            const double value = sum / (downsample * downsample);
            surface.heights[std::size_t(y) * surface.width + x] = float(value * depth);
            const double t = smoothstep(0.35, 0.8, value);
            for (int c = 0; c < 3; ++c) surface.albedo.at(x, y, c) = float(hollow[c] + t * (ridge[c] - hollow[c]));
        }
    return surface;
}

Image relief_normals(const ReliefSurface& surface)
{
    Image normals(surface.width, surface.height, 3);
    for (int y = 0; y < surface.height; ++y)
        for (int x = 0; x < surface.width; ++x) {
            const Vec3 n = normal_at(surface, x, y);
            for (int c = 0; c < 3; ++c) normals.at(x, y, c) = float(n[c]);
        }
    return normals;
}

Image shade_relief(const ReliefSurface& surface, const Vec3& light)
{
    const Vec3 l = checked_light_direction(light, "light");
    const double highest = *std::max_element(surface.heights.begin(), surface.heights.end());
    const double horizontal = std::hypot(l[0], l[1]);
    // Half-texel steps along the ground; a light at the zenith casts no shadow.
    const double step = horizontal > 1e-9 ? 0.5 / horizontal : 0;
    // The bilinear surface lies up to this far below the texel-centre heights along a step.
    constexpr double bias = 1e-3;
    Image image(surface.width, surface.height, 3);
    for (int y = 0; y < surface.height; ++y)
        for (int x = 0; x < surface.width; ++x) {
            const Vec3 n = normal_at(surface, x, y);
            const double cosine = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
            double radiance = std::max(0.0, cosine);
            if (radiance > 0 && step > 0) {
                const double h0 = height_at(surface, x, y);
                for (double t = step; h0 + t * l[2] <= highest; t += step)
                    if (bilinear_height(surface, x + t * l[0], y - t * l[1]) > h0 + t * l[2] + bias) {
                        radiance = 0;
                        break;
                    }
            }
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(surface.albedo.at(x, y, c) * radiance);
        }
    return image;
}

Image crop_periodic(const Image& image, int x, int y, int width, int height)
{
    if (width < 1 || height < 1) throw Error("crop: the size must be positive");
    Image out(width, height, image.channels);
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i)
            for (int c = 0; c < image.channels; ++c)
                out.at(i, j, c) = image.at(wrap(x + i, image.width), wrap(y + j, image.height), c);
    return out;
}

}  // namespace stochtex
