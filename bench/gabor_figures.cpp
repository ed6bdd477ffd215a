// stochtex — renders the pictures of docs/models/gabor.md (not a benchmark; built beside them
// because it links the core's internal Gabor noise for the projected-noise comparison).
//
//   gabor_figures OUTPUT_DIR [EXEMPLAR_DIR]
//
// Writes, as 8-bit sRGB JPEGs:
//   gabor-kinds.jpg       anisotropic / isotropic / hybrid solid noise on a cube
//   gabor-edges.jpg       a cube corner: sliced RP Gabor (continuous) vs kernels projected on
//                         each face (surface Gabor noise, discontinuous)
//   gabor-receding.jpg    a plane receding to the horizon (sandy_rock, else concrete): point
//                         sampling, wavelet band clamping, gabor analytic filtering, and a 64×
//                         supersampled reference of the gabor texture
//   gabor-<name>.jpg      photo | 2D render | solid slice | the solid on a cube, per exemplar
#include "models/gabor/gabor_noise.h"

#include <stochtex/analysis.h>
#include <stochtex/image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>
#include <stochtex/models/gabor_parameters.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace stochtex;
namespace fs = std::filesystem;

/// A pinhole camera looking at the cube [−1, 1]³ from a corner's direction: per pixel the hit
/// point, its face normal and the screen derivatives of the point (ray differentials).
struct CubeView {
    int size;
    Vec3 eye{3.2, 2.4, 2.6}, forward, right, up;
    double focal;

    explicit CubeView(int pixels) : size(pixels)
    {
        forward = normalised({-eye[0], -eye[1], -eye[2]});
        right = normalised(cross(forward, {0, 0, 1}));
        up = cross(right, forward);
        focal = 3.0;
    }
    static Vec3 cross(const Vec3& a, const Vec3& b)
    {
        return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    }
    static Vec3 normalised(const Vec3& v)
    {
        const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        return {v[0] / l, v[1] / l, v[2] / l};
    }
    Vec3 ray(double x, double y) const
    {
        const double sx = (2 * x / size - 1), sy = (1 - 2 * y / size);
        Vec3 d;
        for (int e = 0; e < 3; ++e) d[e] = focal * forward[e] + sx * right[e] + sy * up[e];
        return d;
    }
    /// Hit of the ray through (x, y) with the cube: false when it misses.
    bool hit(double x, double y, Vec3& point, Vec3& normal) const
    {
        const Vec3 d = ray(x, y);
        double t_near = -1e30, t_far = 1e30;
        int axis = -1;
        double sign = 0;
        for (int e = 0; e < 3; ++e) {
            const double t1 = (-1 - eye[e]) / d[e], t2 = (1 - eye[e]) / d[e];
            const double lo = std::min(t1, t2), hi = std::max(t1, t2);
            if (lo > t_near) t_near = lo, axis = e, sign = t1 < t2 ? -1 : 1;
            t_far = std::min(t_far, hi);
        }
        if (t_near > t_far || t_near < 0) return false;
        normal = {0, 0, 0};
        normal[axis] = sign;
        for (int e = 0; e < 3; ++e) point[e] = eye[e] + t_near * d[e];
        return true;
    }
    /// The surface point (scaled to texture units) with dP/dx, dP/dy on the hit face's plane.
    bool surface(int x, int y, double texture_scale, SurfacePoint& s) const
    {
        Vec3 p, n;
        if (!hit(x + 0.5, y + 0.5, p, n)) return false;
        auto on_plane = [&](double sx, double sy) {  // the neighbouring ray meets the same plane
            const Vec3 d = ray(sx, sy);
            const double t = (n[0] * (p[0] - eye[0]) + n[1] * (p[1] - eye[1]) + n[2] * (p[2] - eye[2])) /
                             (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
            return Vec3{eye[0] + t * d[0], eye[1] + t * d[1], eye[2] + t * d[2]};
        };
        const Vec3 px = on_plane(x + 1.5, y + 0.5), py = on_plane(x + 0.5, y + 1.5);
        for (int e = 0; e < 3; ++e) {
            s.p[e] = p[e] * texture_scale;
            s.dpdx[e] = (px[e] - p[e]) * texture_scale;
            s.dpdy[e] = (py[e] - p[e]) * texture_scale;
        }
        s.n = n;
        return true;
    }
};

/// Fills an image row by row on all cores.
Image parallel_image(int width, int height, const std::function<Rgb(int, int)>& pixel)
{
    Image image(width, height, 3);
    const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            for (int y = t; y < height; y += threads)
                for (int x = 0; x < width; ++x) {
                    const Rgb v = pixel(x, y);
                    for (int c = 0; c < 3; ++c) image.at(x, y, c) = v[c];
                }
        });
    for (auto& worker : workers) worker.join();
    return image;
}

Image side_by_side(const std::vector<Image>& panels, int gap = 4)
{
    int width = -gap, height = 0;
    for (const Image& p : panels) width += p.width + gap, height = std::max(height, p.height);
    Image out(width, height, 3);
    std::fill(out.pixels.begin(), out.pixels.end(), 1.0f);
    int x0 = 0;
    for (const Image& p : panels) {
        for (int y = 0; y < p.height; ++y)
            for (int x = 0; x < p.width; ++x)
                for (int c = 0; c < 3; ++c) out.at(x0 + x, y, c) = p.at(x, y, c);
        x0 += p.width + gap;
    }
    return out;
}

const Rgb background{0.9f, 0.9f, 0.9f};

Image cube(const Texture& texture, int size, double texture_scale, bool filter = true)
{
    const CubeView view(size);
    return parallel_image(size, size, [&](int x, int y) {
        SurfacePoint s;
        if (!view.surface(x, y, texture_scale, s)) return background;
        if (!filter) s.dpdx = s.dpdy = {0, 0, 0};
        return texture.eval_solid(s);
    });
}

/// One solid noise octave as a grey texture (mean 0.45, σ 0.15 in linear light).
TextureDescription single_noise(GaborKind kind, const Vec3& direction, double frequency_px, double bandwidth)
{
    TextureDescription d;
    d.model = "gabor";
    d.colour_mode = ColourMode::rgb_shared;
    d.mean = {0.45, 0.45, 0.45};
    d.pixels_per_unit = 256;
    GaborParameters g;
    g.kind = kind;
    g.direction = direction;
    g.bandwidth = bandwidth;
    g.frequencies = {frequency_px};
    g.weights = {std::vector<double>{0.15}, std::vector<double>{0.15}, std::vector<double>{0.15}};
    d.parameters = g;
    return d;
}

void kinds(const fs::path& out)
{
    std::vector<Image> panels;
    const double s = 1.0 / std::sqrt(2.0);
    for (const auto& [kind, direction] : {std::pair{GaborKind::anisotropic, Vec3{s, 0, s}},
                                          std::pair{GaborKind::isotropic, Vec3{0, 0, 1}},
                                          std::pair{GaborKind::hybrid, Vec3{0, 0, 1}}})
        panels.push_back(cube(*make_texture(single_noise(kind, direction, 0.025, 0.6)), 256, 1.0));
    write_image((out / "gabor-kinds.jpg").string(), side_by_side(panels));
}

void edges(const fs::path& out)
{
    // Sliced RP Gabor and, over the same impulses, kernels projected on each face's plane: the
    // 2009 surface noise (ω → ω^s, no slicing phase shift, no w^s weight).
    const TextureDescription d = single_noise(GaborKind::isotropic, {0, 0, 1}, 0.02, 0.6);
    const auto texture = make_texture(d);
    GaborNoiseParameters parameters;  // the same octave, in exemplar pixels
    parameters.kind = GaborKind::isotropic;
    parameters.frequency = 0.02;
    parameters.bandwidth = 0.012;
    parameters.seed = 3;
    const GaborNoise noise(parameters);
    const CubeView view(256);
    const double scale = d.pixels_per_unit;
    auto projected = [&](const Vec3& p, const Vec3& n) {
        double sum = 0;
        const double a = parameters.bandwidth;
        for (const GaborNoise::Impulse& impulse : noise.impulses_near_3d(p)) {
            Vec3 d3{p[0] - impulse.position[0], p[1] - impulse.position[1], p[2] - impulse.position[2]};
            if (d3[0] * d3[0] + d3[1] * d3[1] + d3[2] * d3[2] > noise.radius() * noise.radius()) continue;
            const double h = n[0] * d3[0] + n[1] * d3[1] + n[2] * d3[2];
            const double wn = n[0] * impulse.omega[0] + n[1] * impulse.omega[1] + n[2] * impulse.omega[2];
            double in_plane = 0, phase = 0;
            for (int e = 0; e < 3; ++e) {
                const double pe = d3[e] - h * n[e];
                in_plane += pe * pe, phase += (impulse.omega[e] - wn * n[e]) * pe;
            }
            sum += std::exp(-M_PI * a * a * in_plane) * std::cos(2 * M_PI * phase + impulse.phase[0]);
        }
        return sum;
    };
    // σ of the projected sum, for the same contrast as the sliced panel.
    double sum2 = 0;
    for (int i = 0; i < 2000; ++i) {
        const double v = projected({37.0 * i, 11.0 * i, 5.0 * i}, {0, 0, 1});
        sum2 += v * v / 2000;
    }
    const double gain = 0.15 / std::sqrt(sum2);
    const Image sliced = cube(*texture, 256, 1.0, false);  // world units = texture units
    const Image surface = parallel_image(256, 256, [&](int x, int y) {
        SurfacePoint s;
        if (!view.surface(x, y, scale, s)) return background;
        const float v = float(0.45 + gain * projected(s.p, s.n));
        return Rgb{v, v, v};
    });
    write_image((out / "gabor-edges.jpg").string(), side_by_side({sliced, surface}));
}

/// A plane receding to the horizon (the tests' RecedingPlane, larger): 2D texture coordinates.
struct Receding {
    int width = 320, height = 200;
    double ppu;
    Vec2 at(double x, double y) const
    {
        const double w = 0.015 + 0.985 * (y / height);
        return {(x - width / 2.0) * 0.5 / (w * ppu), (height - y) * 0.5 / (w * ppu)};
    }
    SurfacePoint surface(double x, double y) const
    {
        const Vec2 c = at(x, y), dx = at(x + 1, y), dy = at(x, y + 1);
        SurfacePoint s;
        s.p = {c[0], c[1], 0.3};
        s.dpdx = {dx[0] - c[0], dx[1] - c[1], 0};
        s.dpdy = {dy[0] - c[0], dy[1] - c[1], 0};
        return s;
    }
};

void receding(const fs::path& out, const Image& photo)  // a contrasted photo shows the differences best
{
    AnalysisOptions options;
    options.histogram = HistogramMode::off;
    const TextureDescription wavelet = analyze(photo, options);
    options.model = "gabor";
    const TextureDescription gabor = analyze(photo, options);
    const auto gabor_texture = make_texture(gabor), wavelet_texture = make_texture(wavelet);
    const Receding plane{320, 200, gabor.pixels_per_unit};
    auto panel = [&](const Texture& texture, bool filter) {
        return parallel_image(plane.width, plane.height, [&](int x, int y) {
            SurfacePoint s = plane.surface(x + 0.5, y + 0.5);
            if (!filter) s.dpdx = s.dpdy = {0, 0, 0};
            return texture.eval_solid(s);
        });
    };
    // 64 stratified samples per pixel with the σ = ½ pixel Gaussian (the tests use 256).
    const Image reference = parallel_image(plane.width, plane.height, [&](int x, int y) {
        double sum[3] = {0, 0, 0}, weight_sum = 0;
        for (int j = 0; j < 8; ++j)
            for (int i = 0; i < 8; ++i) {
                const double dx = 1.5 * (2 * (i + 0.5) / 8 - 1), dy = 1.5 * (2 * (j + 0.5) / 8 - 1);
                const double w = std::exp(-2 * (dx * dx + dy * dy));
                SurfacePoint s = plane.surface(x + 0.5 + dx, y + 0.5 + dy);
                s.dpdx = s.dpdy = {0, 0, 0};
                const Rgb v = gabor_texture->eval_solid(s);
                for (int c = 0; c < 3; ++c) sum[c] += w * v[c];
                weight_sum += w;
            }
        return Rgb{float(sum[0] / weight_sum), float(sum[1] / weight_sum), float(sum[2] / weight_sum)};
    });
    write_image((out / "gabor-receding.jpg").string(),
                side_by_side({panel(*gabor_texture, false), panel(*wavelet_texture, true), panel(*gabor_texture, true), reference}));
}

void exemplar(const fs::path& out, const std::string& name, const Image& full, GaborKind kind)
{
    // A 384² crop keeps the figures small; the texture is analysed from the whole photo.
    AnalysisOptions options;
    options.model = "gabor";
    options.model_options = {{"gabor-kind", to_string(kind)}};
    const TextureDescription d = analyze(full, options);
    const auto texture = make_texture(d);
    const int size = 256;
    Image crop(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) crop.at(x, y, c) = full.at(x, y, c);
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.units_per_pixel = 1.0 / d.pixels_per_unit;
    const Image flat = render(*texture, settings);
    settings.solid = true;
    settings.z = 0.37;
    const Image slice = render(*texture, settings);
    // The cube spans 2 units; show about a photo width across a face.
    const Image solid = cube(*texture, size, 0.5);
    write_image((out / ("gabor-" + name + ".jpg")).string(), side_by_side({crop, flat, slice, solid}));
    std::printf("%s: %s, %zu octaves, bandwidth %.2f\n", name.c_str(), to_string(kind), d.parameters.get<GaborParameters>().frequencies.size(),
                d.parameters.get<GaborParameters>().bandwidth);
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 2) {
        std::fprintf(stderr, "usage: gabor_figures OUTPUT_DIR [EXEMPLAR_DIR]\n");
        return 2;
    }
    try {
        const fs::path out = argv[1];
        fs::create_directories(out);
        kinds(out);
        edges(out);
        const Image concrete = read_image_linear((fs::path(STOCHTEX_SOURCE_DIR) / "data/exemplars/concrete_512.png").string());
        exemplar(out, "concrete", concrete, GaborKind::isotropic);
        if (argc > 2) {
            const fs::path dir = argv[2];
            const Image sandy_rock = read_image_linear((dir / "sandy_rock.png").string());
            receding(out, sandy_rock);
            exemplar(out, "sandy_rock", sandy_rock, GaborKind::isotropic);
            exemplar(out, "sand_dunes", read_image_linear((dir / "sand_dunes.png").string()), GaborKind::anisotropic);
        } else {
            receding(out, concrete);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gabor_figures: %s\n", e.what());
        return 1;
    }
    return 0;
}
