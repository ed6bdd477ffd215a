// An unbounded ptm: the coefficient maps made periodic, then tiled and blended by the texture
// (ptm_texture.h; docs/models/ptm.md, "Unbounded").
#include "spectra/periodic_crop.h"

#include <stochtex/error.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/ptm_parameters.h>

#include <memory>

namespace stochtex {

PtmMaps periodic_ptm_maps(const PtmMaps& maps)
{
    const int width = maps.width(), height = maps.height(), channels = maps.coefficients.channels;
    PtmMaps periodic = maps;
    std::vector<float> plane(std::size_t(width) * height);
    for (int c = 0; c < channels; ++c) {
        for (std::size_t i = 0; i < plane.size(); ++i) plane[i] = maps.coefficients.pixels[i * channels + c];
        const std::vector<float> p = periodic_crop(plane, width, height, width, height);
        for (std::size_t i = 0; i < plane.size(); ++i) periodic.coefficients.pixels[i * channels + c] = p[i];
    }
    return periodic;
}

TextureDescription make_unbounded_ptm(const TextureDescription& ptm, const PtmUnboundedOptions& options)
{
    if (!ptm.parameters.holds<PtmParameters>()) throw Error("unbounded ptm: not a ptm texture (model '" + ptm.model + "')");
    if (!(options.triangle_edge >= 1.0 / 64 && options.triangle_edge <= 1))
        throw Error("unbounded ptm: the triangle edge must be in [1/64, 1] maps widths, got " +
                    std::to_string(options.triangle_edge));
    const PtmMaps& maps = *ptm.parameters.get<PtmParameters>().maps;
    if (maps.width() < 2 || maps.height() < 2) throw Error("unbounded ptm: the maps need at least 2x2 texels");
    TextureDescription unbounded = options.make_periodic ? make_ptm_description(periodic_ptm_maps(maps), ptm.parameters.get<PtmParameters>().light)
                                                         : ptm;
    unbounded.pixels_per_unit = ptm.pixels_per_unit;
    unbounded.provenance = ptm.provenance;
    unbounded.parameters.get<PtmParameters>().coefficient_file.clear();
    unbounded.parameters.get<PtmParameters>().unbounded = true;
    unbounded.parameters.get<PtmParameters>().triangle_edge = options.triangle_edge;
    unbounded.seed = options.seed;
    return unbounded;
}

}  // namespace stochtex
