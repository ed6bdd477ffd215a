// The blocks every .stex file shares, whatever its model — scale, colour, histograms, provenance
// and the image layout — each declared once, as a model declares its `parameters` block
// (schema/parameter_schema.h): the reader, the writer, the checks and the tables of
// docs/stex-format.md come from these declarations. stex_file.cpp puts the blocks together.
#pragma once

#include "schema/parameter_schema.h"

#include <stochtex/stex_file.h>
#include <stochtex/texture_description.h>

namespace stochtex {

/// `scale`: members of TextureDescription (read into one, not a struct of its own).
const ParameterSchema<TextureDescription>& scale_block();
/// `colour`: space, mode, mean, basis and the optional chroma_given_brightness.
const ParameterSchema<TextureDescription>& colour_block();
/// One entry of `histograms` (the array holds three, each such an object or null).
const ParameterSchema<HistogramMap>& histogram_block();
/// `provenance`, with the optional `model_choice` list.
const ParameterSchema<Provenance>& provenance_block();
/// `image`: every key optional (a missing one keeps its default), written in full.
const ParameterSchema<ImageLayout>& image_block();

}  // namespace stochtex
