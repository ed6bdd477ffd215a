#include <stochtex/describe.h>
#include <stochtex/texture.h>

#include "gabor_noise.h"
#include "gabor_texture.h"
#include "lrp_texture.h"
#include "ptm_texture.h"
#include "tiling_texture.h"
#include "wavelet_noise.h"
#include "wavelet_texture.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace stochtex {

namespace {
std::string format(const char* pattern, double a, double b = 0, double c = 0)
{
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, pattern, a, b, c);
    return buffer;
}
}  // namespace

std::string describe(const TextureDescription& d)
{
    std::ostringstream out;
    out << "model        " << d.model << " (format version " << d.version << ")\n";
    out << "seed         " << d.seed << "\n";
    out << "scale        " << d.pixels_per_unit << " exemplar pixels per texture unit; unit = " << d.unit_size_m
        << " m\n";
    if (!d.provenance.source.empty())
        out << "source       " << d.provenance.source << " (" << d.provenance.source_width << "x"
            << d.provenance.source_height << ", " << d.provenance.input_colour_space << ")\n";
    out << "colour       " << to_string(d.colour_mode) << ", " << d.colour_space << "\n";
    out << "mean         " << format("%.5f %.5f %.5f", d.mean[0], d.mean[1], d.mean[2]) << "\n";
    for (int r = 0; r < 3; ++r)
        out << (r == 0 ? "basis        " : "             ") << format("%+.4f %+.4f %+.4f", d.basis[r][0], d.basis[r][1], d.basis[r][2])
            << "\n";
    for (int c = 0; c < 3; ++c) {
        out << "histogram " << c << "  ";
        if (!d.histograms[c].enabled()) {
            out << "off (Gaussian)\n";
            continue;
        }
        out << d.histograms[c].z.size() << " knots, values " << format("%.4f .. %.4f", d.histograms[c].value.front(), d.histograms[c].value.back())
            << "\n";
    }
    if (d.wavelet) {
        const double band_variance = WaveletNoise2D::shared().variance();
        out << "sigma_N^2    " << format("%.4f (2D band), %.4f (3D band)", band_variance, WaveletNoise3D::shared().variance())
            << "\n";
        out << "band  cycles/exemplar px     w[0]      w[1]      w[2]\n";
        const auto& w = d.wavelet->band_weights;
        for (std::size_t j = 0; j < w[0].size(); ++j)
            out << format("%4.0f  [1/%-5.0f, 1/%-5.0f)", double(j), std::ldexp(1.0, int(j) + 2), std::ldexp(1.0, int(j) + 1))
                << format("  %8.5f  %8.5f  %8.5f", w[0][j], w[1][j], w[2][j]) << "\n";
        for (int c = 0; c < 3; ++c)
            out << "sigma_M[" << c << "]   " << format("%.5f", wavelet_channel_sigma(w[c])) << "\n";
    }
    if (d.gabor) {
        const GaborParameters& g = *d.gabor;
        out << "gabor        " << to_string(g.kind);
        if (g.kind != GaborKind::isotropic)
            out << format(g.kind == GaborKind::anisotropic ? ", frequency direction (%.3f, %.3f, %.3f)"
                                                           : ", frequency plane normal (%.3f, %.3f, %.3f)",
                          g.direction[0], g.direction[1], g.direction[2]);
        out << "; bandwidth a/F " << format("%.3g", g.bandwidth) << ", " << format("%.3g", g.impulses_per_kernel)
            << " impulses per kernel\n";
        out << "octave  cycles/px  wavelength px  kernel radius px     w[0]      w[1]      w[2]\n";
        for (std::size_t k = 0; k < g.frequencies.size(); ++k) {
            const double f = g.frequencies[k];
            out << format("%6.0f  %9.5f  %13.1f", double(k), f, 1 / f)
                << format("  %16.1f", GaborNoise::support_radius(g.bandwidth * f))
                << format("  %8.5f  %8.5f  %8.5f", g.weights[0][k], g.weights[1][k], g.weights[2][k]) << "\n";
        }
        for (int c = 0; c < 3; ++c)
            out << "sigma_M[" << c << "]   " << format("%.5f", gabor_channel_sigma(g.weights[c]))
                << " (octaves have unit variance, 2D and sliced)\n";
    }
    if (d.tiling) out << describe_tiling(d);
    if (d.ptm) out << describe_ptm(d);
    if (d.lrp) out << describe_lrp(d);
    const Rgb mean = make_texture(d)->mean();
    out << "texture mean " << format("%.5f %.5f %.5f", mean[0], mean[1], mean[2]) << " (limit of minification)\n";
    return out.str();
}

}  // namespace stochtex
