#include "commands.h"

#include "compare_figure.h"
#include "progress_bar.h"

#include <stochtex/atomic_write.h>
#include <stochtex/bake.h>
#include <stochtex/describe.h>
#include <stochtex/error.h>
#include <stochtex/metrics.h>
#include <stochtex/model.h>
#include <stochtex/morph.h>
#include <stochtex/osl/osl_shader.h>
#include <stochtex/pov/pov_include.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace stex_cli {

using namespace stochtex;

std::pair<int, int> parse_size(const std::string& text, const char* option)
{
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w <= 0 || h <= 0 ||
        w > 65536 || h > 65536)
        throw Error(std::string(option) + ": expected WxH with 1 ≤ W, H ≤ 65536 (e.g. 512x512), got '" + text + "'");
    return {w, h};
}

namespace {

CLI::Validator finite_number_at_least_zero(bool zero_allowed)
{
    return CLI::Validator(
        [zero_allowed](std::string& text) {
            double value = 0;
            const bool ok = CLI::detail::lexical_cast(text, value) && std::isfinite(value) &&
                            (zero_allowed ? value >= 0 : value > 0);
            return ok ? std::string() : std::string(zero_allowed ? "expected a finite number ≥ 0" : "expected a finite number > 0") +
                                            ", got '" + text + "'";
        },
        zero_allowed ? "NONNEGATIVE" : "POSITIVE");
}

}  // namespace

CLI::Validator positive_number() { return finite_number_at_least_zero(false); }
CLI::Validator non_negative_number() { return finite_number_at_least_zero(true); }

std::vector<std::string> analysable_models()
{
    std::vector<std::string> names{automatic_model};
    for (const ModelInfo* model : registered_model_infos())
        if (model->capabilities.analysis) names.push_back(model->name);
    return names;
}

std::string model_option_help()
{
    std::string help = "Texture model (stex models: what each can do):\n  auto: fit each model below, score its render "
                       "against the photo (the table is printed and kept in the .stex), keep the closest; of those "
                       "within 10 % of it, the smallest file";
    for (const ModelInfo* model : registered_model_infos())
        if (model->capabilities.analysis) help += "\n  " + model->name + ": " + model->summary + " (" + model->doc + ")";
    return help;
}

void AnalyzeCommand::add_model_options(CLI::App& command)
{
    // Each option once, with the models that declare it (two models may share a name).
    std::map<std::string, std::string> help;
    std::vector<std::string> order;
    for (const ModelInfo* model : registered_model_infos())
        for (const ParameterInfo& option : model->analysis_options) {
            if (!help.count(option.key)) order.push_back(option.key);
            std::string& text = help[option.key];
            text += (text.empty() ? "" : "; ") + model->name + ": " + option.doc + " (" + option.range +
                    (option.unit.empty() ? "" : " " + option.unit) + "; default " + option.default_value + ")";
        }
    for (const std::string& key : order) {
        auto& [value, cli_option] = model_options_[key];
        cli_option = command.add_option("--" + key, value, help[key]);
    }
}

int AnalyzeCommand::run() const
{
    const auto start = std::chrono::steady_clock::now();
    check_output_path(output, "the texture");  // before the analysis: a typo costs nothing
    ImageReadOptions read_options;
    read_options.input_colour_space = colour_space;
    const Image image = read_image_linear(photo, read_options);
    AnalysisOptions options;
    options.model = model;
    options.colour_mode = colour_mode_from_string(colour);
    options.try_colour_modes = colour_option && colour_option->count() == 0;
    options.histogram = histogram_mode_from_string(histogram);
    options.joint_colour = joint_colour == "on";
    options.try_joint_colour = joint_colour == "auto";  // with --model auto; a named model: off
    options.structure_in_choice = choice_structure;
    options.histogram_knots = knots;
    options.max_bands = bands;
    // Only what the user gave: the model checks it (and names options it does not have).
    for (const auto& [key, given] : model_options_)
        if (given.second->count() > 0) options.model_options.emplace_back(key, given.first);
    options.seed = seed;
    options.unit_size_m = unit_size_m;
    options.source_name = std::filesystem::path(photo).filename().string();
    options.input_colour_space = colour_space.empty() ? "file" : colour_space;
    const TextureDescription description = analyze(image, options, terminal_progress_bar());
    write_stex(output, description);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fputs(format_model_choice(description).c_str(), stdout);
    std::printf("wrote %s (%s, %zu bytes) from %s (%dx%d) in %.2f s\n", output.c_str(), description.model.c_str(),
                std::size_t(std::filesystem::file_size(output)), photo.c_str(), image.width, image.height, seconds);
    return 0;
}

int RenderCommand::run() const
{
    check_image_output(output);  // the format and the folder, before the render
    TextureDescription description = read_stex(texture);
    if (seed >= 0) {
        if (seed > 0xffffffffll) throw Error("--seed: must fit in 32 bits");
        description.seed = std::uint32_t(seed);
    }
    RenderSettings settings;
    if (!size.empty()) {
        std::tie(settings.width, settings.height) = parse_size(size, "--size");
    } else if (description.provenance.source_width > 0) {
        settings.width = description.provenance.source_width;
        settings.height = description.provenance.source_height;
    }
    // One output pixel covers `scale` exemplar pixels: scale 1 looks like the photo.
    settings.units_per_pixel = scale / description.pixels_per_unit;
    settings.origin_u = origin_u;
    settings.origin_v = origin_v;
    settings.solid = solid;
    settings.z = z;
    settings.filter = !no_filter;
    settings.threads = threads;
    if (tileable && solid) throw Error("--tileable: solid renders are not periodic; drop --solid or --tileable");
    // The core checks these bounds too (render(), make_periodic_texture()); checked here first
    // so that the message names the option.
    const double ppu = description.pixels_per_unit;
    check_position(origin_u, ppu, "--u");
    check_position(origin_v, ppu, "--v");
    if (solid) check_position(z, ppu, "--z");
    check_position(origin_u + settings.width * settings.units_per_pixel, ppu, "--scale: the image's right edge, --u + width × scale");
    check_position(origin_v + settings.height * settings.units_per_pixel, ppu, "--scale: the image's bottom edge, --v + height × scale");
    // A tileable image is exactly one period of the periodic texture: it wraps without a seam.
    const auto texture_object =
        tileable ? make_periodic_texture(description, {settings.width * settings.units_per_pixel,
                                                       settings.height * settings.units_per_pixel})
                 : make_texture(description);
    const auto start = std::chrono::steady_clock::now();
    const Image image = stochtex::render(*texture_object, settings, terminal_progress_bar());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_image(output, image);
    std::printf("wrote %s (%dx%d, %s, %.1f Mpixel/s)\n", output.c_str(), image.width, image.height,
                solid ? "solid slice" : "2D", image.pixel_count() / seconds * 1e-6);
    return 0;
}

int ModelsCommand::run() const
{
    if (json) {
        std::fputs(models_json().c_str(), stdout);
        return 0;
    }
    for (const ModelInfo* model : registered_model_infos()) {
        if (markdown) {
            std::printf("### %s\n\n%s", model->name.c_str(), parameter_table_markdown(*model).c_str());
            continue;
        }
        const ModelCapabilities& c = model->capabilities;
        std::string can;
        for (const auto& [has, word] : std::initializer_list<std::pair<bool, const char*>>{
                 {c.analysis, "analyze"}, {c.solid, "solid"}, {c.morph, "morph"}, {c.pov_procedural, "pov-procedural"},
                 {c.osl, "osl"}, {c.light_direction, "light"}, {c.gaussian_channels, "gaussian-channels"},
                 {c.joint_colour, "joint-colour"}})
            if (has) can += (can.empty() ? "" : ", ") + std::string(word);
        std::printf("%-8s %s\n         can: %s; %s\n", model->name.c_str(), model->summary.c_str(),
                    can.empty() ? "render" : can.c_str(), model->doc.c_str());
    }
    return 0;
}

int InfoCommand::run() const
{
    const TextureDescription description = read_stex(texture);
    std::printf("%s  (%zu bytes)\n%s", texture.c_str(), std::size_t(std::filesystem::file_size(texture)),
                describe(description).c_str());
    return 0;
}

int CompareCommand::run() const
{
    ImageReadOptions read_options;
    read_options.input_colour_space = colour_space;
    if (!output.empty()) check_image_output(output, "the figure");
    const Image photo_image = read_image_linear(photo, read_options);
    const TextureDescription description = read_stex(texture);
    const Image synthesis =
        render_at_photo_scale(description, photo_image.width, photo_image.height, 0, terminal_progress_bar());
    const ComparisonReport report = compare_images(photo_image, synthesis);
    std::printf("%s vs %s (%dx%d, at the photo's pixel scale)\n%s", photo.c_str(), texture.c_str(), photo_image.width,
                photo_image.height, format_report(report).c_str());
    if (output.empty()) return 0;

    write_image(output, compare_figure(photo_image, synthesis, report, std::filesystem::path(photo).filename().string(),
                                       std::filesystem::path(texture).filename().string() + " (" + description.model +
                                           ")")
                            .image);
    std::printf("wrote %s (photo and synthesis, radial power spectra, luma histograms, 2D luma power spectra, "
                "structure distance)\n",
                output.c_str());
    return 0;
}

int MorphCommand::run() const
{
    check_output_path(output, "the texture");
    const TextureDescription result = stochtex::morph(read_stex(a), read_stex(b), t);
    write_stex(output, result);
    std::printf("wrote %s (t = %g between %s and %s)\n", output.c_str(), t, a.c_str(), b.c_str());
    return 0;
}

int PovCommand::run() const
{
    const auto start = std::chrono::steady_clock::now();
    pov::PovIncludeOptions options;
    options.name = name.empty() ? pov::pov_name_from_path(output) : name;
    pov::validate_pov_name(options.name);  // before any work: a typo costs nothing
    const TextureDescription description = read_stex(texture);
    // Joint colour has no procedural form (POV-Ray cannot multiply patterns): baked by default.
    const bool procedural_form =
        pov::has_procedural_form(description.model) && !description.chroma_given_brightness.enabled();
    options.mode = !mode.empty()    ? pov::pov_mode_from_string(mode)
                   : procedural_form ? pov::PovMode::procedural
                                     : pov::PovMode::baked;
    const std::filesystem::path include_path(output);
    // The baked image sits beside the include, which refers to it by file name only.
    const std::filesystem::path image_path = std::filesystem::path(include_path).replace_extension(".exr");
    if (options.mode == pov::PovMode::baked && image_path == include_path)
        throw Error(output + ": the include would overwrite its own baked image; name it .inc");
    check_output_path(include_path.string(), "the include");
    if (options.mode == pov::PovMode::baked) check_image_output(image_path.string(), "the baked image");
    options.image_file_name = image_path.filename().string();
    options.bake_size = bake_size;
    options.source_name = std::filesystem::path(texture).filename().string();
    const pov::PovInclude include = pov::make_pov_include(description, options);
    if (!include.baked_image.empty()) write_image(image_path.string(), include.baked_image);
    write_file_atomically(include_path.string(), include.text);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wrote %s (%s mode, texture %s, %zu bytes) in %.2f s\n%s\n", output.c_str(), pov::to_string(options.mode),
                options.name.c_str(), include.text.size(), seconds, include.summary.c_str());
    return 0;
}

int BakeCommand::run() const
{
    TextureDescription description = read_stex(texture);
    if (seed >= 0) {
        if (seed > 0xffffffffll) throw Error("--seed: must fit in 32 bits");
        description.seed = std::uint32_t(seed);
    }
    const auto start = std::chrono::steady_clock::now();
    if (!positions.empty()) {
        bake_solid_map(description, positions, output, position_scale, threads, terminal_progress_bar());
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("wrote %s (the solid texture at the positions of %s) in %.2f s\n", output.c_str(), positions.c_str(),
                    seconds);
        return 0;
    }
    // The bake's period bounds its positions; the core checks it too, without the option's name.
    check_position(size * scale / description.pixels_per_unit, description.pixels_per_unit,
                   "--scale: the bake's period, size × scale");
    BakeOptions options;
    options.width = options.height = size;
    options.scale = scale;
    options.tile_size = tile;
    options.half = half;
    options.threads = threads;
    const BakeSummary summary = bake_mip_image(description, output, options, terminal_progress_bar());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wrote %s (%dx%d, %d MIP levels, %s, one period: %.6g x %.6g texture units) in %.2f s\n", output.c_str(),
                size, size, summary.levels, half ? "half" : "float", summary.period_u, summary.period_v, seconds);
    return 0;
}

int OslCommand::run() const
{
    namespace fs = std::filesystem;
    osl::OslShaderOptions options;
    options.shader_name = name.empty() ? osl::osl_shader_name_from_path(output) : name;
    check_output_path(output, "the shader");
    const TextureDescription description = read_stex(texture);
    options.source_name = fs::path(texture).filename().string();
    // The images go beside the shader; the shader names them by absolute path unless
    // --tile-dir says where the renderer will find them.
    const fs::path folder = fs::absolute(fs::path(output)).parent_path();
    const std::string stem = fs::path(output).stem().string();
    const osl::OslImagePaths written = osl::osl_image_paths(description, folder.string(), stem);
    options.images = osl::osl_image_paths(description, tile_dir.empty() ? folder.string() : tile_dir, stem);
    std::string text;
    try {
        text = osl::make_osl_shader(description, options);
    } catch (const Error& e) {
        throw Error(texture + ": " + e.what());  // which texture has no OSL form
    }
    osl::write_osl_images(description, written);
    write_file_atomically(output, text);
    std::string images;
    for (const std::string& path : written.all()) images += (images.empty() ? "" : ", ") + path;
    std::printf("wrote %s (shader %s, %zu bytes) and the images it reads: %s\n", output.c_str(),
                options.shader_name.c_str(), text.size(), images.c_str());
    return 0;
}

}  // namespace stex_cli
