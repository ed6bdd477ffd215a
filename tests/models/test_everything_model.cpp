// A model that exists only in the test suite and declares every capability a model can bring
// with it: fitted from a photo, a true solid texture, morphing (with σ_M per channel), an OSL form
// (test_everything_osl.cpp), a procedural POV-Ray form (test_everything_pov.cpp) and a `stex`
// command of its own (test_everything_cli.cpp). It shows the recipe of docs/architecture.md,
// "How to add a model": its files register themselves, and nothing outside them changes.
// (test_noise_model.cpp is the model with no capability at all.) Solid value noise: trilinear
// over a hashed lattice, faded to the mean as the footprint covers a cell.
#include "models/model.h"
#include "models/test_everything_parameters.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace stochtex::test {

namespace {

class TestEverythingTexture final : public Texture {
public:
    TestEverythingTexture(const TextureDescription& d, const Vec2* period)
        : Texture(d), p_(d.parameters.get<TestEverythingParameters>())
    {
        for (int axis = 0; axis < 2; ++axis) {
            // Periodic in u and v: a whole number of cells per period, the lattice wrapping.
            cells_[axis] = period ? std::max(1.0, std::round(p_.frequency * (*period)[axis])) : 0;
            frequency_[axis] = period ? cells_[axis] / (*period)[axis] : p_.frequency;
        }
    }
    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override
    {
        return colour({uv[0], uv[1], 0}, footprint.major_axis());
    }
    Rgb eval_solid(const SurfacePoint& point) const override
    {
        const double extent = std::max(std::hypot(point.dpdx[0], point.dpdx[1], point.dpdx[2]),
                                       std::hypot(point.dpdy[0], point.dpdy[1], point.dpdy[2]));
        return colour(point.p, extent);
    }
    Rgb mean() const override
    {
        const auto& m = description().mean;
        return {float(m[0]), float(m[1]), float(m[2])};
    }

private:
    Rgb colour(const Vec3& p, double footprint) const
    {
        const double fade = std::clamp(1 - footprint * p_.frequency, 0.0, 1.0);
        const double x = p[0] * frequency_[0], y = p[1] * frequency_[1], z = p[2] * p_.frequency;
        const double x0 = std::floor(x), y0 = std::floor(y), z0 = std::floor(z);
        const double fx = x - x0, fy = y - y0, fz = z - z0;
        double n = 0;
        for (int corner = 0; corner < 8; ++corner) {
            const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
            n += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz) * lattice(x0 + dx, y0 + dy, z0 + dz);
        }
        Rgb rgb;
        for (int c = 0; c < 3; ++c) rgb[c] = float(description().mean[c] + fade * p_.amplitude * n);
        return rgb;
    }
    double lattice(double x, double y, double z) const
    {
        if (cells_[0] > 0) x -= cells_[0] * std::floor(x / cells_[0]), y -= cells_[1] * std::floor(y / cells_[1]);
        std::uint64_t h = std::uint64_t(std::int64_t(x)) * 0x9e3779b97f4a7c15ull ^
                          std::uint64_t(std::int64_t(y)) * 0xc2b2ae3d27d4eb4full ^
                          std::uint64_t(std::int64_t(z)) * 0x165667b19e3779f9ull;
        h ^= description().seed + (h >> 29);
        h *= 0xbf58476d1ce4e5b9ull;
        return double(h >> 11) * 0x1.0p-52 - 1;  // uniform in [−1, 1)
    }
    TestEverythingParameters p_;
    double cells_[2]{}, frequency_[2]{};
};

ParameterSchema<TestEverythingParameters> test_everything_schema()
{
    ParameterSchema<TestEverythingParameters> s;
    s.number("frequency", &TestEverythingParameters::frequency, {0.5, 1024, ""}, {"4", "cells / unit", "lattice frequency"});
    s.number("amplitude", &TestEverythingParameters::amplitude, {0, 1, ""}, {"0.1", "", "noise amplitude"});
    return s;
}

ModelCapabilities every_capability()
{
    ModelCapabilities can;
    // gaussian_channels too: morphing analysed textures interpolates their histogram maps, which
    // takes each channel's σ_M.
    can.analysis = can.solid = can.morph = can.pov_procedural = can.osl = can.gaussian_channels = true;
    return can;
}

class TestEverythingModel final : public ModelOf<TestEverythingParameters> {
public:
    TestEverythingModel()
        : ModelOf({"test_everything", "solid value noise with every capability, for the test suite only",
                   "tests/models/test_everything_model.cpp", every_capability(), {}, {}},
                  test_everything_schema())
    {
    }
    std::unique_ptr<Texture> make_texture(const TextureDescription& d) const override
    {
        return std::make_unique<TestEverythingTexture>(d, nullptr);
    }
    std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& d, const Vec2& period) const override
    {
        return std::make_unique<TestEverythingTexture>(d, &period);
    }
    std::string describe(const TextureDescription& d) const override
    {
        const auto& p = parameters(d);
        return "test everything   " + std::to_string(p.frequency) + " cells per unit, amplitude " +
               std::to_string(p.amplitude) + "\n";
    }
    /// Cells of 8 photo pixels (a texture unit is the photo's width), and a tenth of the first
    /// decorrelated channel's spread: enough to be fitted from the photo, not a fidelity claim.
    ModelParameters fit(const FitInput& input, Provenance&) const override
    {
        const std::vector<float>& values = input.channels[0];
        double sum = 0, squares = 0;
        for (float v : values) sum += v, squares += double(v) * v;
        const double n = double(values.size()), mean = sum / n;
        TestEverythingParameters p;
        p.frequency = std::clamp(input.width / 8.0, 0.5, 1024.0);
        p.amplitude = std::clamp(0.1 * std::sqrt(std::max(0.0, squares / n - mean * mean)), 0.0, 1.0);
        return p;
    }
    /// The lattice values' σ (uniform in [−1, 1): 1/√3) times the amplitude, as at the lattice points.
    double channel_sigma(const TextureDescription& d, int) const override { return parameters(d).amplitude / std::sqrt(3.0); }
    ModelParameters morph(const TextureDescription& a, const TextureDescription& b, double t) const override
    {
        const TestEverythingParameters &pa = parameters(a), &pb = parameters(b);
        return TestEverythingParameters{pa.frequency + t * (pb.frequency - pa.frequency),
                                        pa.amplitude + t * (pb.amplitude - pa.amplitude)};
    }
};

const TestEverythingModel model;
const ModelRegistration registration(model);

}  // namespace

}  // namespace stochtex::test
