// Block synthesis (image quilting, Efros & Freeman 2001) of a multichannel field, as paper 004
// §IV/VI use it on PTM coefficients: blocks in raster order, each chosen at random among the
// exemplar blocks whose causal neighbourhood (the overlap with what is already placed) is
// near-best, joined by a minimum-error cut or a cross-fade. The first `matched` channels are
// compared and cut on; any further channels travel with their block (lrgb chroma).
#pragma once

#include <stochtex/image.h>
#include <stochtex/models/ptm.h>

namespace stochtex {

Image quilt(const Image& exemplar, int matched, const PtmSynthesisOptions& options, PtmSynthesisReport* report,
            const ProgressCallback& progress);

}  // namespace stochtex
