// The two ways an include can express a texture (pov_include.h), each in its own file.
#pragma once

#include <stochtex/pov/pov_include.h>

namespace stochtex::pov {

/// procedural_include.cpp: POV-Ray evaluates the texture, through the model's registered form.
PovInclude make_procedural_include(const TextureDescription& description, const PovIncludeOptions& options);
/// baked_include.cpp: one tileable period rendered by the core, mapped as a linear EXR.
PovInclude make_baked_include(const TextureDescription& description, const PovIncludeOptions& options);

}  // namespace stochtex::pov
