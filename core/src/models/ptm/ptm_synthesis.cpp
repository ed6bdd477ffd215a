// PTM synthesis in ψ-space (paper 004 §VI): quilting of the Legendre coefficient maps. The
// maps are already in the orthonormal basis, so the squared distance between coefficient
// vectors is the L2 distance between reflectance functions on [−1, 1]², and a cross-fade of
// coefficients is the same cross-fade of the functions.
#include <stochtex/error.h>
#include <stochtex/models/ptm.h>

#include "models/ptm/quilting.h"

namespace stochtex {

const char* to_string(SeamMode mode) { return mode == SeamMode::min_cut ? "min-cut" : "blend"; }

SeamMode seam_mode_from_string(const std::string& name)
{
    for (SeamMode mode : {SeamMode::min_cut, SeamMode::blend})
        if (name == to_string(mode)) return mode;
    throw Error("unknown seam mode '" + name + "' (valid: min-cut, blend)");
}

PtmMaps synthesize_ptm(const PtmMaps& exemplar, const PtmSynthesisOptions& options, PtmSynthesisReport* report,
                       const ProgressCallback& progress)
{
    if (exemplar.coefficients.channels != ptm_channel_count(exemplar.colour))
        throw Error("PTM synthesis: the exemplar maps have the wrong channel count");
    PtmMaps result;
    result.colour = exemplar.colour;
    // lrgb: blocks are matched and cut on the luminance function; the chroma travels with its
    // block (blended seams mix chroma linearly: exact for the functions only where the chroma
    // of both sides agrees).
    result.coefficients = quilt(exemplar.coefficients, ptm_function_channel_count(exemplar.colour), options, report, progress);
    return result;
}

}  // namespace stochtex
