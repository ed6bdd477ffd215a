// stochtex — colour statistics of an RGB image: channel means, colour covariance, CIELAB chroma
// and the false-colour rate (analysis/colour_statistics.h).
#include "analysis/colour_statistics.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace stochtex {
namespace {
using Matrix3 = std::array<std::array<double, 3>, 3>;
}  // namespace

double relative_frobenius_error(const Matrix3& reference, const Matrix3& test) {
    double difference_squared = 0, reference_squared = 0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const double d = test[r][c] - reference[r][c];
            difference_squared += d * d;
            reference_squared += reference[r][c] * reference[r][c];
        }
    if (reference_squared == 0)
        throw Error("covariance_relative_error: the reference image is constant (zero colour covariance)");
    return std::sqrt(difference_squared / reference_squared);
}

void require_rgb(const Image& image, const char* role) {
    if (image.channels != 3 || image.empty())
        throw Error(std::string(role) + " image: expected a non-empty 3-channel RGB image, got " +
                    std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                    std::to_string(image.channels) + " channels");
}

std::array<double, 2> cielab_chroma(float r, float g, float b) {
    // Linear Rec.709 → XYZ (D65), relative to the white point; then CIE 1976 L*a*b*'s f, whose
    // linear toe handles dark and negative (out-of-gamut render) values without a cube root of < 0.
    const double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    const double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    const auto f = [](double t) {
        constexpr double delta = 6.0 / 29.0;
        return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29.0;
    };
    return {500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

namespace {

// ΔE*ab ≈ 2.3 is one just-noticeable difference (Sharma 2003): a bin is one JND wide, so the
// one-bin dilation forgives a chroma within about a JND of one the photo has.
constexpr double kChromaBin = 2.3, kChromaLow = -128.0;
constexpr int kChromaBins = 112;  // ⌈256 / 2.3⌉: a*, b* ∈ [−128, 128) (outliers clamp to the edge)
constexpr double kChromaHeld = 0.995;

int chroma_bin_of(const float* p) {
    const std::array<double, 2> chroma = cielab_chroma(p[0], p[1], p[2]);
    const int i = std::clamp(int(std::floor((chroma[0] - kChromaLow) / kChromaBin)), 0, kChromaBins - 1);
    const int j = std::clamp(int(std::floor((chroma[1] - kChromaLow) / kChromaBin)), 0, kChromaBins - 1);
    return j * kChromaBins + i;
}

}  // namespace

/// The a*b* bins a test pixel may fall in without counting as false colour: the densest bins
/// holding kChromaHeld of the reference's pixels, dilated by one bin.
std::vector<char> held_chroma_region(const Image& reference) {
    std::vector<double> counts(kChromaBins * kChromaBins, 0.0);
    for (std::size_t p = 0; p < reference.pixel_count(); ++p) counts[chroma_bin_of(&reference.pixels[p * 3])] += 1;
    std::vector<int> order(counts.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::sort(order.begin(), order.end(), [&](int u, int v) { return counts[u] > counts[v]; });
    std::vector<char> held(counts.size(), 0), region(counts.size(), 0);
    double cumulative = 0;
    for (int bin : order) {
        if (cumulative >= kChromaHeld * double(reference.pixel_count())) break;
        held[bin] = 1;
        cumulative += counts[bin];
    }
    for (int j = 0; j < kChromaBins; ++j)
        for (int i = 0; i < kChromaBins; ++i) {
            if (!held[j * kChromaBins + i]) continue;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int u = i + di, v = j + dj;
                    if (u >= 0 && v >= 0 && u < kChromaBins && v < kChromaBins) region[v * kChromaBins + u] = 1;
                }
        }
    return region;
}

double outside_region_rate(const std::vector<char>& region, const Image& test) {
    std::size_t outside = 0;
    for (std::size_t p = 0; p < test.pixel_count(); ++p) outside += !region[chroma_bin_of(&test.pixels[p * 3])];
    return double(outside) / double(test.pixel_count());
}

double false_colour_rate(const Image& reference, const Image& test) {
    require_rgb(reference, "false_colour_rate: reference");
    require_rgb(test, "false_colour_rate: test");
    return outside_region_rate(held_chroma_region(reference), test);
}

std::array<double, 3> channel_means(const Image& rgb) {
    require_rgb(rgb, "channel_means:");
    std::array<double, 3> sum{};
    for (std::size_t i = 0; i < rgb.pixel_count(); ++i)
        for (int c = 0; c < 3; ++c) sum[c] += rgb.pixels[i * 3 + c];
    for (double& s : sum) s /= double(rgb.pixel_count());
    return sum;
}

/// Population covariance (divides by the pixel count): a texture is the whole population.
Matrix3 colour_covariance(const Image& rgb) {
    const std::array<double, 3> mean = channel_means(rgb);
    Matrix3 covariance{};
    for (std::size_t i = 0; i < rgb.pixel_count(); ++i) {
        double d[3];
        for (int c = 0; c < 3; ++c) d[c] = rgb.pixels[i * 3 + c] - mean[c];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) covariance[r][c] += d[r] * d[c];
    }
    for (auto& row : covariance)
        for (double& v : row) v /= double(rgb.pixel_count());
    return covariance;
}

double covariance_relative_error(const Image& reference, const Image& test) {
    return relative_frobenius_error(colour_covariance(reference), colour_covariance(test));
}

}  // namespace stochtex
