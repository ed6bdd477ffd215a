#include <stochtex/models/shader_colour_data.h>

#include "colour/gaussian.h"
#include "colour/histogram_map.h"

namespace stochtex {

ShaderColourData shader_colour_data(const TextureDescription& description)
{
    ShaderColourData data;
    data.mean = description.mean;
    data.basis = description.basis;
    data.chroma_given_brightness = description.chroma_given_brightness;
    for (int c = 0; c < 3; ++c) {
        const HistogramMap& map = description.histograms[c];
        if (!map.enabled()) continue;
        // The tangents are the core's own (after its limiter), never recomputed by an exporter.
        const MonotoneCubic curve(map.z, map.value);
        data.histogram[c] = {map.z, map.value, curve.slopes()};
    }
    const GaussHermite& rule = GaussHermite::standard_normal();
    data.gh_node.assign(rule.node.begin(), rule.node.end());
    data.gh_weight.assign(rule.weight.begin(), rule.weight.end());
    return data;
}

}  // namespace stochtex
