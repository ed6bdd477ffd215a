// `stex tiling …`: tiling textures that are not analysed from one colour photo
// (docs/models/tiling.md): colour-mapped noise pairs, phasor noise, normal maps from a height
// photo, and the LEAN-filtered shading of a normal map. (`stex analyze --model tiling` covers
// colour photos.)
// The model's own command: it registers itself below and is compiled into `stex`
// (cli/CMakeLists.txt), not the core.
#include "command_registry.h"
#include "commands.h"
#include "progress_bar.h"

#include <stochtex/atomic_write.h>
#include <stochtex/error.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/tiling.h>
#include <stochtex/models/tiling_parameters.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace stex_cli {

using namespace stochtex;

class TilingCommands : public Command {
public:
    /// Registers the tiling command and its sub-commands on `app`.
    explicit TilingCommands(CLI::App& app);
    ~TilingCommands();
    bool selected() const override;
    /// Runs the chosen sub-command; throws stochtex::Error for bad input.
    int run() const override;

private:
    struct Options;
    std::unique_ptr<Options> options_;
};

struct TilingCommands::Options {
    CLI::App* tiling = nullptr;
    CLI::App *colour_map = nullptr, *phasor = nullptr, *normal_map = nullptr, *shade = nullptr;
    std::string noise_a, noise_b, map = "green", output, height, texture, profile = "sine", size = "512x512";
    double frequency = 1.0 / 16, strength = 4.0, scale = 1.0, roughness = 0.08, albedo = 0.5, specular = 0.04;
    std::vector<double> light{0.5, 0.3, 0.81};
    bool no_lean = false, no_filter = false;
    TilingSourceOptions source;
    int threads = 0;
};

namespace {

void add_source_options(CLI::App* command, TilingSourceOptions& source)
{
    command->add_option("--exemplar-size", source.exemplar_size, "Largest exemplar side (a power of two is used), 16 to 1024")
        ->check(CLI::Range(16, 1024))->capture_default_str();
    command->add_option("--exemplar-bits", source.bits, "Bits per stored exemplar sample (8 or 16)")
        ->check(CLI::IsMember({8, 16}))->capture_default_str();
    command->add_option("--seed", source.seed, "Seed stored in the texture")->capture_default_str();
    command->add_option("--filter-taps", source.filter_taps,
                        "Footprint estimator taps per axis: 1 (the paper's single estimate) renders ~2.4x faster, 2 halves "
                        "the filtered mean's error (docs/models/tiling.md)")
        ->check(CLI::Range(1, TilingParameters::max_filter_taps))->capture_default_str();
}

void write(const std::string& path, const TextureDescription& description)
{
    write_stex(path, description);
    std::printf("wrote %s (tiling, output %s, %zu bytes)\n", path.c_str(), to_string(description.parameters.get<TilingParameters>().output),
                std::size_t(std::filesystem::file_size(path)));
}

}  // namespace

TilingCommands::TilingCommands(CLI::App& app) : options_(std::make_unique<Options>())
{
    Options& o = *options_;
    o.tiling = app.add_subcommand("tiling", "Tiling textures from noise pairs, phasor noise or height maps; LEAN shading");
    o.tiling->require_subcommand(1);

    o.colour_map = o.tiling->add_subcommand("colour-map", "Two noise photos index a 2D colour map (colour-mapped noise vector field)");
    o.colour_map->add_option("noise_a", o.noise_a, "Photo whose luminance is noise a (the map's x)")->required();
    o.colour_map->add_option("noise_b", o.noise_b, "Photo whose luminance is noise b (the map's y)")->required();
    o.colour_map->add_option("--map", o.map, "Colour map: green (smooth) or rgb (saturated, discontinuous)")
        ->check(CLI::IsMember({"green", "rgb"}))->capture_default_str();
    o.colour_map->add_option("-o,--output", o.output, "Output .stex file")->required();
    add_source_options(o.colour_map, o.source);

    o.phasor = o.tiling->add_subcommand("phasor", "Phasor noise as a colour-mapped (sin, cos) pair with a profile map");
    o.phasor->add_option("--profile", o.profile, "Profile of the phase: sine, square or sawtooth")
        ->check(CLI::IsMember({"sine", "square", "sawtooth"}))->capture_default_str();
    o.phasor->add_option("--frequency", o.frequency, "Stripe frequency, cycles per exemplar pixel")
        ->check(CLI::Range(1.0 / 256, 0.5))->capture_default_str();
    o.phasor->add_option("-o,--output", o.output, "Output .stex file")->required();
    add_source_options(o.phasor, o.source);

    o.normal_map = o.tiling->add_subcommand("normal-map", "A height photo's slopes, tiled and blended: a LEAN-filtered normal map");
    o.normal_map->add_option("height", o.height, "Height photo (luminance is height)")->required();
    o.normal_map->add_option("--strength", o.strength, "Height units per luminance unit, per exemplar pixel")
        ->check(positive_number())->capture_default_str();
    o.normal_map->add_option("-o,--output", o.output, "Output .stex file")->required();
    add_source_options(o.normal_map, o.source);

    o.shade = o.tiling->add_subcommand("shade", "Render a normal-map tiling texture shaded (Lambert + Gaussian specular lobe)");
    o.shade->add_option("texture", o.texture, ".stex file with output normal_map")->required();
    o.shade->add_option("-o,--output", o.output, "Output image")->required();
    o.shade->add_option("--size", o.size, "Output size WxH")->capture_default_str();
    o.shade->add_option("--scale", o.scale, "Exemplar pixels per output pixel")->check(positive_number())->capture_default_str();
    o.shade->add_option("--light", o.light, "Direction towards the light, tangent space (x y z, z > 0)")->expected(3);
    o.shade->add_option("--roughness", o.roughness, "Base slope standard deviation of the facets")
        ->check(positive_number())->capture_default_str();
    o.shade->add_option("--albedo", o.albedo, "Lambert albedo")->check(CLI::Range(0.0, 1.0))->capture_default_str();
    o.shade->add_option("--specular", o.specular, "Specular weight")->check(CLI::Range(0.0, 100.0))->capture_default_str();
    o.shade->add_flag("--no-lean", o.no_lean, "Shade the filtered mean normal only (no slope covariance): the aliasing-prone way");
    o.shade->add_flag("--no-filter", o.no_filter, "Point-sample instead of filtering each pixel's footprint");
    o.shade->add_option("--threads", o.threads, "Worker threads (0: all cores)")->check(non_negative_number());
}

TilingCommands::~TilingCommands() = default;

bool TilingCommands::selected() const { return bool(*options_->tiling); }

int TilingCommands::run() const
{
    Options& o = *options_;
    if (*o.colour_map || *o.phasor || *o.normal_map) check_output_path(o.output, "the texture");
    else check_image_output(o.output);  // shade: before the render
    if (*o.colour_map) {
        o.source.source_name = std::filesystem::path(o.noise_a).filename().string() + " + " +
                               std::filesystem::path(o.noise_b).filename().string();
        write(o.output, colour_mapped_texture(read_image_linear(o.noise_a), read_image_linear(o.noise_b), o.map, o.source));
        return 0;
    }
    if (*o.phasor) {
        o.source.source_name = "phasor noise";
        write(o.output, phasor_texture("phasor-" + o.profile, o.frequency, o.source));
        return 0;
    }
    if (*o.normal_map) {
        o.source.source_name = std::filesystem::path(o.height).filename().string();
        // A height map holds data, not colour: its values are read as they are (no sRGB decoding).
        ImageReadOptions raw;
        raw.input_colour_space = "linear";
        write(o.output, normal_map_texture(read_image_linear(o.height, raw), o.strength, o.source));
        return 0;
    }
    const TextureDescription description = read_stex(o.texture);
    NormalMapShading shading;
    shading.light = {o.light[0], o.light[1], o.light[2]};
    shading.base_roughness = o.roughness;
    shading.lean = !o.no_lean;
    shading.albedo = o.albedo;
    shading.specular = o.specular;
    RenderSettings settings;
    if (!o.size.empty()) std::tie(settings.width, settings.height) = parse_size(o.size, "--size");
    settings.units_per_pixel = o.scale / description.pixels_per_unit;
    settings.filter = !o.no_filter;
    settings.threads = o.threads;
    const Image image = render(*make_shaded_normal_map(description, shading), settings, terminal_progress_bar());
    write_image(o.output, image);
    std::printf("wrote %s (%dx%d, %s shading)\n", o.output.c_str(), image.width, image.height, o.no_lean ? "mean-normal" : "LEAN");
    return 0;
}

const CommandRegistration tiling_registration = register_command<TilingCommands>(HelpPosition::model_command, {"tiling"});

}  // namespace stex_cli
