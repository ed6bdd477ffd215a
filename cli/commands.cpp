#include "commands.h"

#include "command_registry.h"
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

// ---- analyze ---------------------------------------------------------------------------------

void AnalyzeCommand::add_options(CLI::App& a)
{
    a.add_option("photo", photo, "Photo of a stochastic texture (any format OpenImageIO reads)")->required();
    a.add_option("-o,--output", output, "Output .stex file")->required();
    // Models and their own options come from the registry: each model's declared options
    // (name, range, default, doc) become options here, and the core checks their values.
    a.add_option("--model", model, model_option_help())->check(CLI::IsMember(analysable_models()))->capture_default_str();
    colour_option =
        a.add_option("--colour", colour,
                     "Colour mode: pca (decorrelated), rgb (independent), rgb-shared (with --model auto and no "
                     "--colour, each model is also tried in the other modes it declares: tiling in rgb)")
            ->check(CLI::IsMember({"pca", "rgb", "rgb-shared"}))
            ->capture_default_str();
    a.add_option("--histogram", histogram,
                 "Histogram matching: on, off, or auto (per channel, when it brings the histogram measurably closer)")
        ->check(CLI::IsMember({"auto", "on", "off"}))->capture_default_str();
    a.add_option("--joint-colour", joint_colour,
                 "Joint colour (pca colour; wavelet, gabor and lrp): on ties each chroma axis's value and spread to "
                 "brightness, as in the photo (independent channels make colours the photo never had: gravel's "
                 "false-colour rate 14.7 % -> 1.7 %); off keeps three independent channels, which POV-Ray's "
                 "procedural mode needs (stex pov bakes a joint-colour texture); auto: with --model auto each of "
                 "those models is fitted both ways and the scores decide, a named model is fitted without")
        ->check(CLI::IsMember({"auto", "on", "off"}))->capture_default_str();
    a.add_flag("--choice-structure", choice_structure,
               "With --model auto: score the candidates also by the structure distance (a seventh term of the "
               "fidelity penalty, target 0.25; docs/metrics.md, Structure), and try tiling's sharper blends "
               "(blend contrast 4, 8) and, on photos 512 px across, a 512^2 exemplar. A row replaces the default's "
               "choice only where it is no worse on the six other targets, on the scoring render and at the "
               "photo's full size. About 5-8x the analysis time");
    a.add_option("--knots", knots, "Knots of each histogram map")->check(CLI::Range(4, 64))->capture_default_str();
    a.add_option("--bands", bands, "Keep at most N finest bands (gabor: octaves) (0: all the photo supports)")
        ->check(CLI::Range(0, 24))->capture_default_str();
    add_model_options(a);
    a.add_option("--seed", seed, "Seed stored in the texture")->capture_default_str();
    a.add_option("--colourspace,--colorspace", colour_space,
                 "Colour space of the photo's values (default: what the file says, else sRGB)");
    a.add_option("--unit-size", unit_size_m, "Physical width of the photo in metres (for scenes)")
        ->check(positive_number())->capture_default_str();
}

const CommandRegistration analyze_registration = register_options_command<AnalyzeCommand>(
    HelpPosition::analyze, "analyze", "Analyse a texture photo into a .stex procedural texture");

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

// ---- render ----------------------------------------------------------------------------------

void RenderCommand::add_options(CLI::App& r)
{
    r.add_option("texture", texture, ".stex file")->required();
    r.add_option("-o,--output", output, "Output image (.exr, .png, .jpg, .tif)")->required();
    r.add_option("--size", size, "Output size WxH (default: the analysed photo's size)");
    r.add_option("--scale", scale, "Exemplar pixels per output pixel (2: zoomed out ×2)")
        ->check(positive_number())->capture_default_str();
    r.add_option("--u", origin_u, "Texture-space u of the image's left edge (texture units)")->capture_default_str();
    r.add_option("--v", origin_v, "Texture-space v of the image's top edge (texture units)")->capture_default_str();
    r.add_flag("--solid", solid, "Evaluate the solid (3D) texture on the plane w = Z");
    r.add_option("--z", z, "Depth of the solid slice (texture units)")->capture_default_str();
    r.add_flag("--no-filter", no_filter, "Point-sample instead of filtering each pixel's footprint");
    r.add_flag("--tileable", tileable,
               "Make the image one period of the texture, so it tiles without a seam (band frequencies snap to fit)");
    r.add_option("--threads", threads, "Worker threads (0: all cores)")->check(non_negative_number())->capture_default_str();
    r.add_option("--seed", seed, "Override the texture's seed")->check(non_negative_number());
}

const CommandRegistration render_registration = register_options_command<RenderCommand>(
    HelpPosition::render, "render", "Render a .stex texture to an image (EXR: scene-linear; PNG/JPEG: sRGB)");

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

// ---- models ----------------------------------------------------------------------------------

void ModelsCommand::add_options(CLI::App& command)
{
    command.add_flag("--json", json, "Machine-readable: the registry as JSON (name, summary, capabilities, parameters, options)");
    command.add_flag("--markdown", markdown, "Each model's .stex parameter table, as in docs/stex-format.md");
}

const CommandRegistration models_registration = register_options_command<ModelsCommand>(
    HelpPosition::models, "models", "List the texture models: what each is for, what it can do, its parameters");

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
    // The blocks every model's file shares, as declared (docs/stex-format.md holds these tables too).
    if (markdown)
        for (const StexBlockInfo& block : shared_stex_blocks())
            std::printf("### block %s\n\n%s", block.path.c_str(), parameter_table_markdown(block.fields, block.path).c_str());
    return 0;
}

// ---- info ------------------------------------------------------------------------------------

void InfoCommand::add_options(CLI::App& command) { command.add_option("texture", texture, ".stex file")->required(); }

const CommandRegistration info_registration = register_options_command<InfoCommand>(
    HelpPosition::info, "info", "Print a .stex texture's parameters and statistics");

int InfoCommand::run() const
{
    const TextureDescription description = read_stex(texture);
    std::printf("%s  (%zu bytes)\n%s", texture.c_str(), std::size_t(std::filesystem::file_size(texture)),
                describe(description).c_str());
    return 0;
}

// ---- compare ---------------------------------------------------------------------------------

void CompareCommand::add_options(CLI::App& c)
{
    c.add_option("photo", photo, "The photo")->required();
    c.add_option("texture", texture,
                 ".stex file, rendered at the photo's size; or an image (a host's render, an experiment's output), "
                 "scored as it is")
        ->required();
    c.add_option("-o,--output", output, "Side-by-side PNG: photo, synthesis, their PSDs and histograms");
    c.add_option("--colourspace,--colorspace", colour_space, "Colour space of the photo's values");
}

const CommandRegistration compare_registration = register_options_command<CompareCommand>(
    HelpPosition::compare, "compare", "Compare a photo with a texture: metrics, and a side-by-side figure");

int CompareCommand::run() const
{
    ImageReadOptions read_options;
    read_options.input_colour_space = colour_space;
    if (!output.empty()) check_image_output(output, "the figure");
    const Image photo_image = read_image_linear(photo, read_options);
    // An image is scored as it is (read with the photo's colour space); a .stex is rendered at
    // the photo's pixel scale and size.
    const bool is_stex = std::filesystem::path(texture).extension() == ".stex";
    std::string label = std::filesystem::path(texture).filename().string();
    Image synthesis;
    if (is_stex) {
        const TextureDescription description = read_stex(texture);
        synthesis = render_at_photo_scale(description, photo_image.width, photo_image.height, 0, terminal_progress_bar());
        label += " (" + description.model + ")";
    } else {
        synthesis = read_image_linear(texture, read_options);  // RGB, as the photo (grey is replicated)
    }
    const ComparisonReport report = compare_images(photo_image, synthesis);
    std::printf("%s vs %s (%dx%d%s)\n%s", photo.c_str(), texture.c_str(), synthesis.width, synthesis.height,
                is_stex ? ", at the photo's pixel scale" : ", as it is", format_report(report).c_str());
    if (output.empty()) return 0;

    write_image(output, compare_figure(photo_image, synthesis, report, std::filesystem::path(photo).filename().string(),
                                       label)
                            .image);
    std::printf("wrote %s (photo and synthesis, radial power spectra, luma histograms, 2D luma power spectra, "
                "structure distance)\n",
                output.c_str());
    return 0;
}

// ---- morph -----------------------------------------------------------------------------------

void MorphCommand::add_options(CLI::App& m)
{
    m.add_option("a", a, "Texture at t = 0")->required();
    m.add_option("b", b, "Texture at t = 1")->required();
    m.add_option("--t", t, "Interpolation parameter in [0, 1]")->check(CLI::Range(0.0, 1.0))->capture_default_str();
    m.add_option("-o,--output", output, "Output .stex file")->required();
}

const CommandRegistration morph_registration = register_options_command<MorphCommand>(
    HelpPosition::morph, "morph", "Interpolate two textures of the same model");

int MorphCommand::run() const
{
    check_output_path(output, "the texture");
    const TextureDescription result = stochtex::morph(read_stex(a), read_stex(b), t);
    write_stex(output, result);
    std::printf("wrote %s (t = %g between %s and %s)\n", output.c_str(), t, a.c_str(), b.c_str());
    return 0;
}

// ---- pov -------------------------------------------------------------------------------------

void PovCommand::add_options(CLI::App& p)
{
    p.add_option("texture", texture, ".stex file")->required();
    p.add_option("-o,--output", output, "Output include (.inc); baked mode also writes the image beside it (.exr)")->required();
    p.add_option("--name", name, "Identifier prefix in the include (default: from the output file name)");
    p.add_option("--mode", mode, "procedural (POV-Ray evaluates it: solid, unlimited) or baked (an image map; any model); "
                                 "default: procedural where the model allows it")
        ->check(CLI::IsMember({"procedural", "baked"}));
    p.add_option("--bake-size", bake_size, "Baked mode: texels per side, 16 to 8192 (0: one texture unit at the photo's pixel scale, at most 2048)")
        ->check(CLI::Range(0, 8192))->capture_default_str();
}

const CommandRegistration pov_registration = register_options_command<PovCommand>(
    HelpPosition::pov, "pov", "Write a POV-Ray 3.7 include: the texture as SDL (procedural) or a baked tileable EXR");

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

// ---- bake ------------------------------------------------------------------------------------

void BakeCommand::add_options(CLI::App& b)
{
    b.add_option("texture", texture, ".stex file")->required();
    b.add_option("-o,--output", output, "Output image (.exr)")->required();
    b.add_option("--size", size, "Level-0 texels per side")->check(CLI::Range(8, 32768))->capture_default_str();
    b.add_option("--scale", scale, "Exemplar pixels per texel (1: the photo's pixel scale)")
        ->check(positive_number())->capture_default_str();
    b.add_option("--tile", tile, "Tile size (a power of two, 8 to 4096)")->capture_default_str();
    b.add_flag("--half", half, "Store 16-bit half floats instead of 32-bit floats");
    b.add_option("--threads", threads, "Worker threads (0: all cores)")->check(non_negative_number())->capture_default_str();
    b.add_option("--seed", seed, "Override the texture's seed")->check(non_negative_number());
    b.add_option("--positions", positions,
                 "Instead: the solid texture at the texels of this position map (RGBA float: xyz, alpha = covered), "
                 "e.g. a UV atlas of object coordinates baked by Blender");
    b.add_option("--position-scale", position_scale, "With --positions: texture units per position unit")
        ->check(positive_number())->capture_default_str();
}

const CommandRegistration bake_registration = register_options_command<BakeCommand>(
    HelpPosition::bake, "bake", "Bake a texture into a tiled, MIP-mapped EXR: one seamless period, each level filtered by the model");

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

// ---- osl -------------------------------------------------------------------------------------

void OslCommand::add_options(CLI::App& o)
{
    o.add_option("texture", texture, ".stex file")->required();
    o.add_option("-o,--output", output, "Output shader (.osl); the images it reads are written beside it (docs/osl.md)")->required();
    o.add_option("--name", name, "Shader name (default: stochtex_ + the output file's name)");
    o.add_option("--tile-dir", tile_dir, "Folder the shader names for the images it reads (default: the output's folder, absolute)");
}

const CommandRegistration osl_registration = register_options_command<OslCommand>(
    HelpPosition::osl, "osl", "Write an OSL shader with the texture's parameters built in (wavelet, gabor, tiling) and the images it reads");

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
