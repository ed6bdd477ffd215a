// Measuring relighting and derived maps against a known truth (the acceptance numbers of
// docs/models/ptm.md; `stex ptm relight --compare`, `stex ptm export-maps --reference-…`).
#include <stochtex/error.h>
#include <stochtex/models/ptm.h>

#include "models/ptm/ptm_functions.h"
#include "numerics/constants.h"
#include "spectra/spectral_orientation.h"

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {


std::vector<float> luma(const Image& image)
{
    std::vector<float> plane(image.pixel_count());
    for (std::size_t i = 0; i < plane.size(); ++i)
        for (int c = 0; c < 3; ++c) plane[i] += float(luma_weights[c] * image.pixels[i * 3 + c]);
    return plane;
}

void moments(const std::vector<float>& values, double& mean, double& sigma)
{
    double sum = 0, squares = 0;
    for (float v : values) sum += v, squares += double(v) * v;
    mean = sum / double(values.size());
    sigma = std::sqrt(std::max(0.0, squares / double(values.size()) - mean * mean));
}

void check_same_size(const Image& a, const Image& b, const char* what)
{
    if (a.width != b.width || a.height != b.height || a.channels != 3 || b.channels != 3)
        throw Error(std::string(what) + ": the images must be RGB of one size (" + std::to_string(a.width) + "x" +
                    std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
}

}  // namespace

double RelitComparison::orientation_error_degrees() const
{
    return std::fabs(std::remainder(orientation_test.angle_degrees - orientation_truth.angle_degrees, 180.0));
}

RelitComparison compare_relit(const Image& truth, const Image& test)
{
    if (truth.channels != 3 || test.channels != 3) throw Error("compare_relit: RGB images expected");
    const std::vector<float> a = luma(truth), b = luma(test);
    RelitComparison result;
    moments(a, result.mean_truth, result.sigma_truth);
    moments(b, result.mean_test, result.sigma_test);
    result.w1 = wasserstein1(a, b) / result.sigma_truth;
    result.log_psd_db = log_psd_distance_db(radial_psd(a, truth.width, truth.height), radial_psd(b, test.width, test.height));
    result.orientation_truth = spectral_orientation(a, truth.width, truth.height);
    result.orientation_test = spectral_orientation(b, test.width, test.height);
    if (truth.width == test.width && truth.height == test.height) {
        double sum = 0;
        for (std::size_t i = 0; i < truth.pixels.size(); ++i) sum += std::pow(double(truth.pixels[i]) - test.pixels[i], 2);
        result.pixel_rmse = std::sqrt(sum / double(truth.pixels.size()));
    }
    return result;
}

NormalErrors compare_normals(const Image& estimated, const Image& truth)
{
    check_same_size(estimated, truth, "compare_normals");
    std::vector<double> angles(truth.pixel_count());
    for (std::size_t i = 0; i < angles.size(); ++i) {
        double dot = 0, length_a = 0, length_b = 0;
        for (int c = 0; c < 3; ++c) {
            const double a = estimated.pixels[i * 3 + c], b = truth.pixels[i * 3 + c];
            dot += a * b, length_a += a * a, length_b += b * b;
        }
        angles[i] = std::acos(std::clamp(dot / std::sqrt(length_a * length_b), -1.0, 1.0)) * 180 / kPi;
    }
    std::sort(angles.begin(), angles.end());
    NormalErrors errors;
    for (double a : angles) errors.mean += a / double(angles.size());
    errors.median = angles[angles.size() / 2];
    errors.percentile_90 = angles[angles.size() * 9 / 10];
    return errors;
}

double mean_relative_error(const Image& estimate, const Image& truth)
{
    check_same_size(estimate, truth, "mean_relative_error");
    double sum = 0;
    for (std::size_t i = 0; i < truth.pixels.size(); ++i)
        sum += std::fabs(estimate.pixels[i] - truth.pixels[i]) / std::max(1e-6f, truth.pixels[i]);
    return sum / double(truth.pixels.size());
}

}  // namespace stochtex
