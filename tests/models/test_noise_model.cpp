// A model that exists only in the test suite: bilinear value noise with two parameters. It is
// here to show that a model is one file — it registers itself and gets .stex reading, writing
// and validation, `stex info`, the conformance suite (model_conformance_test.cpp) and its error
// messages from the registry, with no edit anywhere else.
#include "models/model.h"

#include <cmath>
#include <cstdint>

namespace stochtex::test {

struct TestNoiseParameters {
    double frequency = 4;  ///< lattice cells per texture unit
    double amplitude = 0.1;
};

namespace {

class TestNoiseTexture final : public Texture {
public:
    TestNoiseTexture(const TextureDescription& d, const Vec2* period) : Texture(d), p_(d.parameters.get<TestNoiseParameters>())
    {
        for (int axis = 0; axis < 2; ++axis) {
            // Periodic: a whole number of cells per period, the lattice wrapping.
            cells_[axis] = period ? std::max(1.0, std::round(p_.frequency * (*period)[axis])) : 0;
            frequency_[axis] = period ? cells_[axis] / (*period)[axis] : p_.frequency;
        }
    }
    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override
    {
        const double fade = std::clamp(1 - footprint.major_axis() * p_.frequency, 0.0, 1.0);
        const double x = uv[0] * frequency_[0], y = uv[1] * frequency_[1];
        const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
        const double n = (1 - fy) * ((1 - fx) * lattice(x0, y0) + fx * lattice(x0 + 1, y0)) +
                         fy * ((1 - fx) * lattice(x0, y0 + 1) + fx * lattice(x0 + 1, y0 + 1));
        Rgb rgb;
        for (int c = 0; c < 3; ++c) rgb[c] = float(description().mean[c] + fade * p_.amplitude * n);
        return rgb;
    }
    Rgb eval_solid(const SurfacePoint& point) const override
    {
        return eval({point.p[0], point.p[1]}, {point.dpdx[0], point.dpdx[1], point.dpdy[0], point.dpdy[1]});
    }
    Rgb mean() const override
    {
        const auto& m = description().mean;
        return {float(m[0]), float(m[1]), float(m[2])};
    }

private:
    double lattice(double x, double y) const
    {
        if (cells_[0] > 0) x -= cells_[0] * std::floor(x / cells_[0]), y -= cells_[1] * std::floor(y / cells_[1]);
        std::uint64_t h = std::uint64_t(std::int64_t(x)) * 0x9e3779b97f4a7c15ull ^ std::uint64_t(std::int64_t(y)) * 0xc2b2ae3d27d4eb4full;
        h ^= description().seed + (h >> 29);
        h *= 0xbf58476d1ce4e5b9ull;
        return double(h >> 11) * 0x1.0p-52 - 1;  // uniform in [−1, 1)
    }
    TestNoiseParameters p_;
    double cells_[2]{}, frequency_[2]{};
};

ParameterSchema<TestNoiseParameters> test_noise_schema()
{
    ParameterSchema<TestNoiseParameters> s;
    s.number("frequency", &TestNoiseParameters::frequency, {0.5, 1024, ""}, {"4", "cells / unit", "lattice frequency"});
    s.number("amplitude", &TestNoiseParameters::amplitude, {0, 1, ""}, {"0.1", "", "noise amplitude"});
    return s;
}

class TestNoiseModel final : public ModelOf<TestNoiseParameters> {
public:
    TestNoiseModel() : ModelOf({"test_noise", "value noise, for the test suite only", "tests/models/test_noise_model.cpp", {}, {}, {}}, test_noise_schema()) {}
    std::unique_ptr<Texture> make_texture(const TextureDescription& d) const override
    {
        return std::make_unique<TestNoiseTexture>(d, nullptr);
    }
    std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& d, const Vec2& period) const override
    {
        return std::make_unique<TestNoiseTexture>(d, &period);
    }
    std::string describe(const TextureDescription& d) const override
    {
        const auto& p = parameters(d);
        return "test noise   " + std::to_string(p.frequency) + " cells per unit, amplitude " + std::to_string(p.amplitude) + "\n";
    }
    TextureDescription example() const override
    {
        TextureDescription d;
        d.model = name();
        d.pixels_per_unit = 64;
        d.mean = {0.4, 0.3, 0.2};
        d.parameters = TestNoiseParameters{};
        return d;
    }
};

const TestNoiseModel model;
const ModelRegistration registration(model);

}  // namespace

}  // namespace stochtex::test
