// stochtex — how fast a texture evaluates, on this machine (`stex bench`): the same texture
// through each route a consumer takes, and a baked file through OIIO's TextureSystem as the
// reference, measured in one run.
#pragma once

#include <stochtex/texture_description.h>

#include <string>
#include <vector>

namespace stochtex {

struct ThroughputSettings {
    int size = 512;          ///< rasters of size × size; the baked reference is a size² map
    double scale = 1.0;      ///< exemplar pixels per output pixel (as `stex render --scale`)
    int threads = 0;         ///< 0: all cores
    int repetitions = 5;     ///< timed runs per route; the median is reported
    int tile = 64;           ///< the plugin route's tile side
};

/// One route's median rate (million evaluated pixels, or lookups, per second of wall time).
struct ThroughputResult {
    std::string route;       ///< "2D raster", "solid slice", "plugin tiles", "baked lookup (warm)", …
    std::string detail;      ///< what was measured, in words (API, sizes, filter)
    double median = 0;       ///< Mpix/s (or M lookups/s)
    double low = 0, high = 0;  ///< the slowest and fastest repetition
};

/// Measures: render() in 2D and as a solid slice (the model's eval_region / eval_solid_region),
/// level 0 of the texture's MipImage filled in tile × tile tiles on `threads` threads (what the
/// OIIO plugin does per tile), and the reference — the same texture baked by bake_mip_image()
/// to a temporary tiled, MIP-mapped EXR and looked up through OIIO's TextureSystem at every
/// texel centre of level 0 with a one-texel footprint (cold: a fresh TextureSystem per
/// repetition; warm: the same lookups again). Every model, through the registry.
/// Throws Error for invalid settings or a description that does not make a texture.
std::vector<ThroughputResult> measure_throughput(const TextureDescription& description, const ThroughputSettings& settings);

}  // namespace stochtex
