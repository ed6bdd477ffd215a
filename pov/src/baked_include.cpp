// Baked mode: the core renders one period of the texture made periodic (make_periodic_texture),
// and the include maps that image (docs/pov.md). Works for every model; POV-Ray then only
// interpolates. The image is float EXR: linear like the core's values, and — unlike an 8/16-bit
// PNG — neither clamped to [0, 1] nor quantised. image_map reads EXR as linear data.
#include "include_modes.h"
#include <stochtex/pov/pov_procedural_form.h>
#include <stochtex/pov/sdl_text.h>

#include <stochtex/error.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stochtex::pov {

namespace {
constexpr int default_max_bake_size = 2048;
constexpr int min_bake_size = 16, max_bake_size = 8192;
}  // namespace

PovInclude make_baked_include(const TextureDescription& description, const PovIncludeOptions& options)
{
    const std::string& n = options.name;
    if (options.image_file_name.empty()) throw Error("baked POV-Ray include: no image file name given");
    if (options.image_file_name.find('"') != std::string::npos)
        throw Error("baked POV-Ray include: the image file name '" + options.image_file_name + "' contains a quote");
    // Default: one texture unit at the photo's own pixel scale, so a texel is an exemplar pixel.
    const int size = options.bake_size > 0
                         ? options.bake_size
                         : std::clamp(int(std::lround(description.pixels_per_unit)), min_bake_size, default_max_bake_size);
    if (size < min_bake_size || size > max_bake_size)
        throw Error("--bake-size " + std::to_string(size) + ": expected " + std::to_string(min_bake_size) + " to " +
                    std::to_string(max_bake_size) + " pixels");
    // Texels keep the photo's pixel size: the period is size exemplar pixels.
    const double period = size / description.pixels_per_unit;

    const auto texture = make_periodic_texture(description, {period, period});
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.units_per_pixel = period / size;
    settings.filter = true;  // each texel is filtered over its own footprint, as the core renders
    PovInclude result;
    result.baked_image = render(*texture, settings);

    char line[200];
    std::snprintf(line, sizeof line, "%dx%d texels over %.6g x %.6g texture units", size, size, period, period);
    result.summary = std::string("baked: ") + line + " -> " + options.image_file_name;

    std::string doc = include_preamble(description, options);
    doc += "\nKnobs (#declare before the #include to override):\n"
           "  " + n + "_Scale       POV-Ray units per texture unit (default: the photo's width in metres)\n"
           "  " + n + "_Image       the baked image (default \"" + options.image_file_name + "\"; POV-Ray looks beside\n"
           "                  the scene and in +L library paths)\n"
           "  " + n + "_Projection  1 (default): box mapping, each surface takes the image projected\n"
           "                  along its normal's dominant axis (hard switch where |n_axis| ~ 0.6);\n"
           "                  0: planar, projected along z only\n"
           "  " + n + "_Finish      the finish of " + n + " (default: ambient 0, diffuse 1: the pigment is an albedo)\n\n"
           "How it is made. The core rendered one period of the texture made periodic (" + line + ",\n"
           "each texel filtered over its footprint) into a float EXR, linear. image_map tiles it with\n"
           "bilinear interpolation (interpolate 2), texel centres at (i + 1/2)/size of the period.\n"
           "Exact: every texel is the core's value (float, neither clamped nor quantised), so mean,\n"
           "histograms and spectrum at the photo's scale are the core's. Approximated: between texels\n"
           "bilinear (no detail finer than an exemplar pixel), no MIP mapping (minified, it aliases:\n"
           "render with +A), the image repeats every period, and on curved or slanted surfaces the\n"
           "projection stretches it (and box mapping switches projection along a seam).\n";

    std::string sdl = sdl_include_begin(n, doc);
    sdl += "// ---- Knobs -------------------------------------------------------------------------\n";
    sdl += sdl_knob(n + "_Scale", sdl_number(description.unit_size_m), "POV-Ray units per texture unit");
    sdl += sdl_knob(n + "_Image", "\"" + options.image_file_name + "\"", "the baked period (linear EXR)");
    sdl += sdl_knob(n + "_Projection", "1", "1: box mapping; 0: planar along z");
    sdl += sdl_knob(n + "_Finish", "finish { ambient 0 diffuse 1 }", "the finish of " + n);

    const Rgb mean = texture->mean();
    sdl += "\n#declare " + n + "_Mean = rgb " + sdl_vector({mean[0], mean[1], mean[2]}) +
           ";  // the texture's expected colour\n";
    sdl += "#declare " + n + "_Period = " + sdl_number(period) + ";  // texture units covered by the image\n";
    sdl += "\n// image_map puts the image on the unit square of the x-y plane, top row at y = 1, and\n"
           "// repeats it: scaled to one period, u runs along +x and v (image rows) along -y.\n";
    sdl += "#declare " + n + "_Along_Z = pigment { image_map { exr " + n + "_Image interpolate 2 } scale " + n +
           "_Period }\n";
    sdl += "#if (" + n + "_Projection = 0)\n"
           "  #declare " + n + "_Projected = pigment { " + n + "_Along_Z }\n"
           "#else\n"
           "  // The same image projected along x and y; `slope` (the normal's direction) picks one.\n"
           "  #declare " + n + "_Along_X = pigment { " + n + "_Along_Z rotate 90 * y }\n"
           "  #declare " + n + "_Along_Y = pigment { " + n + "_Along_Z rotate 90 * x }\n"
           "  #declare " + n + "_Along_Y_Or_Z = pigment {\n"
           "    slope { y }  // 0: normal -y, 1: +y\n"
           "    pigment_map { [0.2 " + n + "_Along_Y] [0.2 " + n + "_Along_Z] [0.8 " + n + "_Along_Z] [0.8 " + n + "_Along_Y] }\n"
           "  }\n"
           "  #declare " + n + "_Projected = pigment {\n"
           "    slope { x }\n"
           "    pigment_map { [0.2 " + n + "_Along_X] [0.2 " + n + "_Along_Y_Or_Z] [0.8 " + n + "_Along_Y_Or_Z] [0.8 " + n +
           "_Along_X] }\n"
           "  }\n"
           "#end\n";
    sdl += "#declare " + n + "_Pigment = pigment { " + n + "_Projected scale " + n + "_Scale }\n";
    sdl += "#declare " + n + " = texture { pigment { " + n + "_Pigment } finish { " + n + "_Finish } }\n";
    sdl += sdl_include_end(n);
    result.text = std::move(sdl);
    return result;
}

}  // namespace stochtex::pov
