// stochtex — a model's procedural POV-Ray form (`stex pov --mode procedural`; docs/pov.md).
//
// The generator names no model: a model whose registry capability `pov_procedural` promises SDL
// that POV-Ray evaluates itself registers its form here (a PovProceduralFormRegistration in
// core/src/models/<name>/front_ends/<name>_pov.cpp, compiled into this front-end, not the core).
// What forms share with the baked mode: sdl_text.h (numbers, knobs, the include's frame),
// include_preamble() below, and POV-Ray's measured noise (pov_noise_calibration.h).
#pragma once

#include <stochtex/pov/pov_include.h>

#include <functional>
#include <string>

namespace stochtex::pov {

struct PovProceduralForm {
    std::string model;  ///< the registry's model name
    /// The include; `options` are validated (name, mode). Throws Error for a texture the form
    /// cannot express, saying why and what to use instead.
    std::function<PovInclude(const TextureDescription&, const PovIncludeOptions&)> include;
};

/// Registers a model's procedural form (a static object of this type in the form's file).
struct PovProceduralFormRegistration {
    explicit PovProceduralFormRegistration(PovProceduralForm form);
};

/// The registered form of `model`, or nullptr.
const PovProceduralForm* find_pov_procedural_form(const std::string& model);

/// The lines every include's header comment starts with: source, model, usage of the declared names.
std::string include_preamble(const TextureDescription& description, const PovIncludeOptions& options);

}  // namespace stochtex::pov
