// Writing POV-Ray SDL text: numbers, vectors, comment blocks and the parts every include shares
// (header, guard, knobs). Kept apart from the modes so that both write the same conventions.
#pragma once

#include <stochtex/texture_description.h>

#include <array>
#include <string>

namespace stochtex::pov {

/// A finite number with 9 significant digits (float precision with margin); throws on NaN/inf,
/// which POV-Ray would otherwise reject far from the cause.
std::string sdl_number(double value);
std::string sdl_vector(const std::array<double, 3>& v);  ///< "<a, b, c>"

/// Prefixes each line of `text` with "// ".
std::string sdl_comment(const std::string& text);

/// `#ifndef (NAME) #declare NAME = value; #end  // comment` — a knob the scene may set first.
std::string sdl_knob(const std::string& identifier, const std::string& value, const std::string& comment);

/// The opening of every include: the documentation comment, the guard and #version 3.7.
/// The text after it must end with sdl_include_end(name).
std::string sdl_include_begin(const std::string& name, const std::string& documentation);
std::string sdl_include_end(const std::string& name);

}  // namespace stochtex::pov
