#include <stochtex/pov/sdl_text.h>

#include <stochtex/error.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace stochtex::pov {

std::string sdl_number(double value)
{
    if (!std::isfinite(value)) throw Error("POV-Ray include: a non-finite number cannot be written to SDL");
    if (value == 0) return "0";  // never "-0"
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

std::string sdl_vector(const std::array<double, 3>& v)
{
    return "<" + sdl_number(v[0]) + ", " + sdl_number(v[1]) + ", " + sdl_number(v[2]) + ">";
}

std::string sdl_comment(const std::string& text)
{
    std::istringstream lines(text);
    std::string line, out;
    while (std::getline(lines, line)) out += line.empty() ? "//\n" : "// " + line + "\n";
    return out;
}

std::string sdl_knob(const std::string& identifier, const std::string& value, const std::string& comment)
{
    return "#ifndef (" + identifier + ") #declare " + identifier + " = " + value + "; #end  // " + comment + "\n";
}

std::string sdl_include_begin(const std::string& name, const std::string& documentation)
{
    // The guard idiom of POV-Ray's own includes: parse once, restore the scene's #version after.
    return sdl_comment(documentation) + "\n#ifndef (" + name + "_Inc_Temp)\n#declare " + name +
           "_Inc_Temp = version;\n#version 3.7;\n\n";
}

std::string sdl_include_end(const std::string& name)
{
    return "\n#version " + name + "_Inc_Temp;\n#end  // " + name + "_Inc_Temp\n";
}

}  // namespace stochtex::pov
