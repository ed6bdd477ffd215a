// stochtex — textures whose appearance depends on a light direction (the ptm model).
//
// A generic hook for front-ends: the OIIO plugin's open-time hint "stex:light", `stex` options
// and add-ons set the light through these functions and never need to know which model, or
// which field of it, holds the direction.
#pragma once

#include <stochtex/footprint.h>
#include <stochtex/texture_description.h>

#include <string>

namespace stochtex {

/// Whether the description's model is evaluated for a light direction.
bool depends_on_light(const TextureDescription& description);
/// The light direction the description is evaluated for; throws Error if it has none.
Vec3 light_direction(const TextureDescription& description);
/// Sets the light direction (any non-zero vector with z > 0; it is normalised). Throws Error
/// naming the model when it does not depend on light, or for an invalid direction.
void set_light_direction(TextureDescription& description, const Vec3& direction);
/// Parses "x,y,z" (three numbers separated by commas and/or spaces) as a direction for
/// set_light_direction: x to the image's right, y to its top, z out of the surface.
Vec3 parse_light_direction(const std::string& text);

}  // namespace stochtex
