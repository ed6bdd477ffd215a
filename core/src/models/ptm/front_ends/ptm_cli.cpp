// `stex ptm …`: relightable textures (docs/models/ptm.md). Fit a PTM to photos under known
// lights, synthesise larger PTMs in ψ-space, relight them, export normal and albedo maps, and
// render the height-field test data with known truth.
// The model's own command: it registers itself below and is compiled into `stex`
// (cli/CMakeLists.txt), not the core.
#include "command_registry.h"
#include "commands.h"
#include "plot.h"
#include "progress_bar.h"

#include <stochtex/atomic_write.h>
#include <stochtex/error.h>
#include <stochtex/lighting.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/relief_shading.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>
#include <stochtex/models/ptm_parameters.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace stex_cli {

using namespace stochtex;

class PtmCommands : public Command {
public:
    /// Registers the ptm command and its sub-commands on `app`.
    explicit PtmCommands(CLI::App& app);
    ~PtmCommands();
    /// Whether the command line chose the ptm command.
    bool selected() const override;
    /// Runs the chosen sub-command; throws stochtex::Error for bad input.
    int run() const override;

private:
    struct Options;
    std::unique_ptr<Options> options_;
};

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double degrees(double radians) { return radians * 180 / M_PI; }

/// "AZ,EL" in degrees: azimuth from +x towards +y (up), elevation above the surface.
Vec3 direction_from_angles(const std::string& text)
{
    double azimuth = 0, elevation = 0;
    char comma = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%lf%c%lf%c", &azimuth, &comma, &elevation, &extra) != 3 || comma != ',' ||
        !(elevation > 0 && elevation <= 90))
        throw Error("--light-angles: expected 'AZIMUTH,ELEVATION' in degrees with 0 < elevation ≤ 90, got '" + text + "'");
    const double a = azimuth * M_PI / 180, e = elevation * M_PI / 180;
    return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

std::string angles_of(const Vec3& l)
{
    char text[64];
    std::snprintf(text, sizeof text, "az %6.1f° el %4.1f°", degrees(std::atan2(l[1], l[0])), degrees(std::asin(std::min(1.0, l[2]))));
    return text;
}

std::array<int, 4> parse_region(const std::string& text)
{
    std::array<int, 4> region{};
    char c1 = 0, c2 = 0, c3 = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c%d%c%d%c", &region[0], &c1, &region[1], &c2, &region[2], &c3, &region[3],
                    &extra) != 7 ||
        c1 != ',' || c2 != ',' || c3 != ',' || region[2] < 8 || region[3] < 8)
        throw Error("--region: expected 'X,Y,W,H' with W, H ≥ 8, got '" + text + "'");
    return region;
}

/// An error relative to the photos' RMS, "(1.23 %" + tail; photos that are all black have no
/// scale to relate to (the ratio would print as "-nan %").
std::string relative_error(double rmse, double data_rms, const char* tail)
{
    char text[96];
    if (data_rms > 0)
        std::snprintf(text, sizeof text, "(%.2f %%%s)", 100 * rmse / data_rms, tail);
    else
        std::snprintf(text, sizeof text, "(no relative error: the photos are black, RMS 0)");
    return text;
}

void print_fit(const PtmFit& fit, const LightSet& lights, bool per_light)
{
    char rms[48];
    std::snprintf(rms, sizeof rms, " of the photos' RMS %.5f", fit.data_rms);
    std::printf("fit residual RMSE %.5f %s\n", fit.rmse, relative_error(fit.rmse, fit.data_rms, rms).c_str());
    if (std::isnan(fit.loo_rmse)) {
        std::printf("leave-one-light-out: undefined (a light alone determines part of the fit; add lights)\n");
        return;
    }
    std::printf("leave-one-light-out RMSE %.5f %s over %zu lights\n", fit.loo_rmse,
                relative_error(fit.loo_rmse, fit.data_rms, "").c_str(), lights.images.size());
    if (!per_light) return;
    std::printf("light  direction             LOO RMSE\n");
    for (std::size_t i = 0; i < lights.images.size(); ++i)
        std::printf("%5zu  %s  %.5f  %s\n", i, angles_of(lights.directions[i]).c_str(), fit.loo_rmse_per_light[i],
                    fs::path(lights.images[i]).filename().c_str());
}

Provenance ptm_provenance(const std::string& source, int width, int height, const std::string& colour_space,
                          std::vector<std::pair<std::string, std::string>> options)
{
    Provenance provenance;
    provenance.source = fs::path(source).filename().string();
    provenance.source_width = width;
    provenance.source_height = height;
    provenance.input_colour_space = colour_space;
    provenance.tool = "stochtex " STOCHTEX_VERSION;
    provenance.options = std::move(options);
    return provenance;
}

void print_comparison(const Image& truth, const Image& test, bool pixelwise)
{
    const RelitComparison c = compare_relit(truth, test);
    std::printf("  mean %.4f vs %.4f (%+.1f %%)  σ %.4f vs %.4f  W1/σ %.3f  log-PSD %.2f dB  orientation %.2f@%+.0f° vs "
                "%.2f@%+.0f°",
                c.mean_truth, c.mean_test, 100 * (c.mean_test / c.mean_truth - 1), c.sigma_truth, c.sigma_test, c.w1,
                c.log_psd_db, c.orientation_truth.strength, c.orientation_truth.angle_degrees, c.orientation_test.strength,
                c.orientation_test.angle_degrees);
    if (pixelwise) {
        if (c.pixel_rmse < 0)
            throw Error("--pixelwise: the truth is " + std::to_string(truth.width) + "x" + std::to_string(truth.height) +
                        ", the render " + std::to_string(test.width) + "x" + std::to_string(test.height));
        std::printf("  pixel RMSE %.5f", c.pixel_rmse);
    }
    std::printf("\n");
}

}  // namespace

struct PtmCommands::Options {
    CLI::App* ptm = nullptr;
    CLI::App *fit = nullptr, *synthesize = nullptr, *relight = nullptr, *export_maps = nullptr, *relief = nullptr,
             *unbounded = nullptr;

    // fit
    std::string lights, output, colour = "lrgb", light = "0,0,1", colour_space;
    bool per_light = false;
    // synthesize
    std::string input, size = "512x512", seam = "min-cut", search = "projection";
    int block = 40, overlap = 8;
    bool tileable = false, verify = false;
    double tolerance = 0.1, min_tolerance = 0.05;
    std::uint32_t seed = 1;
    // relight
    std::vector<std::string> light_vectors, light_angles;
    std::string lights_from, render_size;
    double scale = 1;
    bool compare = false, pixelwise = false;
    // export-maps
    std::string normal_output, albedo_output, estimator = "lambertian", reference_normals, reference_albedo;
    // relief
    std::string height_map;
    int light_count = 40, downsample = 2;
    double min_elevation = 15, azimuth_offset = 0, depth = 24;
    std::string region;
    // unbounded
    double triangle_edge = 0.28867513459481287;
    bool already_periodic = false;

    int run_fit() const;
    int run_synthesize() const;
    int run_relight() const;
    int run_export_maps() const;
    int run_relief() const;
    int run_unbounded() const;
};

PtmCommands::PtmCommands(CLI::App& app) : options_(std::make_unique<Options>())
{
    Options& o = *options_;
    o.ptm = app.add_subcommand("ptm", "Relightable textures: fit a PTM to photos under known lights, synthesise, relight "
                                      "(docs/models/ptm.md)");
    o.ptm->require_subcommand(1, 1);

    o.fit = o.ptm->add_subcommand("fit", "Fit a polynomial texture map to photos under known lights; write a ptm .stex");
    o.fit->add_option("lights", o.lights, "Light sidecar: .lp (count, then 'image x y z' per line) or .json")->required();
    o.fit->add_option("-o,--output", o.output, "Output .stex (the coefficient maps go beside it as <name>.ptm.exr)")->required();
    o.fit->add_option("--colour,--color", o.colour, "lrgb (luminance function × per-texel chroma) or rgb (a function per channel)")
        ->check(CLI::IsMember({"lrgb", "rgb"}))->capture_default_str();
    o.fit->add_option("--light", o.light, "Light direction x,y,z the .stex is evaluated for (x right, y up, z out)")
        ->capture_default_str();
    o.fit->add_option("--colourspace,--colorspace", o.colour_space, "Colour space of the photos (default: what each file says, else sRGB)");
    o.fit->add_flag("--per-light", o.per_light, "Print the leave-one-out error of every light");

    o.synthesize = o.ptm->add_subcommand("synthesize", "Synthesise a larger PTM by quilting in ψ-space (Legendre coefficients)");
    o.synthesize->add_option("input", o.input, "Exemplar ptm .stex")->required();
    o.synthesize->add_option("-o,--output", o.output, "Output ptm .stex")->required();
    o.synthesize->add_option("--size", o.size, "Output size WxH in texels (tileable: rounded up to whole block steps)")
        ->capture_default_str();
    o.synthesize->add_option("--block", o.block, "Block side in texels")->check(CLI::Range(4, 1024))->capture_default_str();
    o.synthesize->add_option("--overlap", o.overlap, "Overlap of neighbouring blocks, 1 … block/2")
        ->check(CLI::Range(1, 512))->capture_default_str();
    o.synthesize->add_flag("--tileable", o.tileable, "Periodic output: wraps without a seam");
    o.synthesize->add_option("--seam", o.seam, "min-cut (boundary cut) or blend (cross-fade)")
        ->check(CLI::IsMember({"min-cut", "blend"}))->capture_default_str();
    o.synthesize->add_option("--tolerance", o.tolerance, "Accept blocks within (1 + T)·best neighbourhood distance …")
        ->check(CLI::Range(0.0, 10.0))->capture_default_str();
    o.synthesize->add_option("--min-tolerance", o.min_tolerance,
                             "… plus this RMS difference per texel, in units of the exemplar's ψ standard deviation")
        ->check(CLI::Range(0.0, 10.0))->capture_default_str();
    o.synthesize->add_option("--seed", o.seed, "Random seed for the choice among accepted blocks")->capture_default_str();
    o.synthesize->add_option("--search", o.search, "projection (rejection by projection kernels) or exhaustive; both return the same blocks")
        ->check(CLI::IsMember({"projection", "exhaustive"}))->capture_default_str();
    o.synthesize->add_flag("--verify", o.verify, "Also run the other search: check the outputs are identical, print the speed-up");

    o.relight = o.ptm->add_subcommand("relight", "Render a ptm .stex under light directions (several: a horizontal strip)");
    o.relight->add_option("input", o.input, "ptm .stex")->required();
    o.relight->add_option("-o,--output", o.output, "Output image (.png/.jpg: sRGB; .exr: scene-linear)")->required();
    o.relight->add_option("--light", o.light_vectors, "Light direction x,y,z (repeatable)");
    o.relight->add_option("--light-angles", o.light_angles, "Light as AZIMUTH,ELEVATION in degrees (repeatable; azimuth from +x towards +y)");
    o.relight->add_option("--lights-from", o.lights_from, "The lights of a sidecar (.lp/.json)");
    o.relight->add_flag("--compare", o.compare, "With --lights-from: compare each render with the sidecar's image of that light");
    o.relight->add_flag("--pixelwise", o.pixelwise, "With --compare: also the pixel RMSE (same surface region only)");
    o.relight->add_option("--size", o.render_size, "Render size WxH (default: the maps' size)");
    o.relight->add_option("--scale", o.scale, "Texels per output pixel (filtered through the MIP-mapped coefficients)")
        ->check(positive_number())->capture_default_str();

    o.export_maps = o.ptm->add_subcommand("export-maps", "Write normal and albedo maps estimated from a ptm .stex");
    o.export_maps->add_option("input", o.input, "ptm .stex")->required();
    o.export_maps->add_option("--normal", o.normal_output, "Normal map (0.5 + 0.5 n, x right, y up; PNG 8-bit or EXR float)");
    o.export_maps->add_option("--albedo", o.albedo_output, "Albedo map (PNG: sRGB; EXR: linear)");
    o.export_maps->add_option("--estimator", o.estimator, "lambertian (least-squares Lambertian fit) or ptm-maximum (Malzbender)")
        ->check(CLI::IsMember({"lambertian", "ptm-maximum"}))->capture_default_str();
    o.export_maps->add_option("--reference-normals", o.reference_normals, "True normal map (same encoding): print angular errors");
    o.export_maps->add_option("--reference-albedo", o.reference_albedo, "True albedo (linear EXR): print relative errors");

    o.unbounded = o.ptm->add_subcommand("unbounded", "Make a ptm .stex unbounded and random-access: its coefficient maps tiled "
                                                     "and blended (same tiles for all fields), relightable");
    o.unbounded->add_option("input", o.input, "ptm .stex (fitted, or synthesised --tileable)")->required();
    o.unbounded->add_option("-o,--output", o.output, "Output ptm .stex (its maps beside it as <name>.ptm.exr)")->required();
    o.unbounded->add_option("--triangle-edge", o.triangle_edge, "Triangle grid edge in maps widths (tiles ≈ 2× this across)")
        ->check(CLI::Range(1.0 / 64, 1.0))->capture_default_str();
    o.unbounded->add_option("--seed", o.seed, "Random seed of the tile offsets")->capture_default_str();
    o.unbounded->add_flag("--already-periodic", o.already_periodic,
                          "The maps tile already (ptm synthesize --tileable): keep them as they are instead of taking "
                          "each channel's periodic component");

    o.relief = o.ptm->add_subcommand("relief", "Test data: render a height map under known lights (Lambertian, cast shadows)");
    o.relief->add_option("height_map", o.height_map, "Grey height map (values are data: never colour-converted)")->required();
    o.relief->add_option("-o,--output", o.output, "Output folder: light_NNN.exr, lights.lp, normal.exr, albedo.exr")->required();
    o.relief->add_option("--lights", o.light_count, "Number of lights (golden-angle spiral over the hemisphere)")
        ->check(CLI::Range(1, 1024))->capture_default_str();
    o.relief->add_option("--min-elevation", o.min_elevation, "Lowest light elevation in degrees")
        ->check(CLI::Range(0.0, 89.0))->capture_default_str();
    o.relief->add_option("--azimuth-offset", o.azimuth_offset, "Rotation of the spiral in degrees (another light set)")
        ->capture_default_str();
    o.relief->add_option("--lights-from", o.lights_from, "Use the directions of this sidecar instead of a spiral");
    o.relief->add_option("--downsample", o.downsample, "Box-filter the height map down by this factor")
        ->check(CLI::Range(1, 16))->capture_default_str();
    o.relief->add_option("--depth", o.depth, "Height range in texels (after downsampling)")->check(positive_number())->capture_default_str();
    o.relief->add_option("--region", o.region, "Write only X,Y,W,H of the (periodic) surface; shadows come from all of it");
}

PtmCommands::~PtmCommands() = default;

bool PtmCommands::selected() const { return bool(*options_->ptm); }

int PtmCommands::run() const
{
    const Options& o = *options_;
    if (*o.fit) return o.run_fit();
    if (*o.synthesize) return o.run_synthesize();
    if (*o.relight) return o.run_relight();
    if (*o.export_maps) return o.run_export_maps();
    if (*o.relief) return o.run_relief();
    if (*o.unbounded) return o.run_unbounded();
    throw Error("ptm: a sub-command is required (fit, synthesize, relight, export-maps, relief, unbounded)");
}

int PtmCommands::Options::run_fit() const
{
    const auto start = Clock::now();
    const Vec3 evaluated_light = parse_light_direction(light);
    check_output_path(output, "the texture");
    const LightSet set = read_light_set(lights);
    ImageReadOptions read_options;
    read_options.input_colour_space = colour_space;
    const std::vector<Image> photos = read_light_set_photos(set, read_options);
    const PtmFit fit = fit_ptm(photos, set.directions, ptm_colour_from_string(colour), terminal_progress_bar());
    TextureDescription description = make_ptm_description(fit.maps, evaluated_light);
    description.provenance =
        ptm_provenance(lights, fit.maps.width(), fit.maps.height(), colour_space.empty() ? "file" : colour_space,
                       {{"command", "ptm fit"}, {"colour", colour}, {"lights", std::to_string(set.images.size())}});
    write_stex(output, description);
    std::printf("wrote %s (%s PTM, %dx%d texels, from %zu photos) in %.2f s\n", output.c_str(), colour.c_str(),
                fit.maps.width(), fit.maps.height(), photos.size(), seconds_since(start));
    print_fit(fit, set, per_light);
    return 0;
}

int PtmCommands::Options::run_synthesize() const
{
    check_output_path(output, "the texture");
    const TextureDescription exemplar = read_stex(input);
    if (!exemplar.parameters.holds<PtmParameters>()) throw Error(input + ": not a ptm texture (model '" + exemplar.model + "')");
    PtmSynthesisOptions options;
    std::tie(options.width, options.height) = parse_size(size, "--size");
    options.block = block;
    options.overlap = overlap;
    options.tileable = tileable;
    options.seam = seam_mode_from_string(seam);
    options.relative_tolerance = tolerance;
    options.absolute_tolerance = min_tolerance;
    options.seed = seed;
    options.brute_force = search == "exhaustive";
    PtmSynthesisReport report;
    const PtmMaps maps = synthesize_ptm(*exemplar.parameters.get<PtmParameters>().maps, options, &report, terminal_progress_bar());
    TextureDescription description = make_ptm_description(maps, exemplar.parameters.get<PtmParameters>().light);
    description.seed = seed;
    description.provenance = ptm_provenance(input, exemplar.parameters.get<PtmParameters>().maps->width(), exemplar.parameters.get<PtmParameters>().maps->height(), "linear",
                                            {{"command", "ptm synthesize"}, {"block", std::to_string(block)},
                                             {"overlap", std::to_string(overlap)}, {"seam", seam},
                                             {"tileable", tileable ? "yes" : "no"}, {"seed", std::to_string(seed)}});
    write_stex(output, description);
    std::printf("wrote %s (%dx%d texels%s, %d blocks of %d with overlap %d, %s seams) in %.2f s, of which search %.2f s (%s)\n",
                output.c_str(), report.width, report.height, tileable ? ", tileable" : "", report.blocks, block, overlap,
                seam.c_str(), report.total_seconds, report.search_seconds, search.c_str());
    if (!report.surviving.empty()) {
        std::printf("rejection: %lld candidate positions;", report.positions);
        for (std::size_t level = 0; level < report.surviving.size(); ++level)
            std::printf(" %.2f %%", 100.0 * report.surviving[level] / std::max(1ll, report.positions));
        std::printf(" left after bound levels 0–%zu; %lld distances computed (%.3f %%)\n", report.surviving.size() - 1,
                    report.exact_distances, 100.0 * report.exact_distances / std::max(1ll, report.positions));
    }
    if (!verify) return 0;
    options.brute_force = !options.brute_force;
    PtmSynthesisReport other;
    const PtmMaps again = synthesize_ptm(*exemplar.parameters.get<PtmParameters>().maps, options, &other, terminal_progress_bar());
    const bool identical = again.coefficients.pixels == maps.coefficients.pixels;
    const PtmSynthesisReport& exhaustive = options.brute_force ? other : report;
    const PtmSynthesisReport& projection = options.brute_force ? report : other;
    std::printf("verify: exhaustive search %.2f s, projection search %.2f s: speed-up ×%.1f; outputs %s\n",
                exhaustive.search_seconds, projection.search_seconds,
                exhaustive.search_seconds / std::max(1e-9, projection.search_seconds),
                identical ? "identical" : "DIFFER");
    return identical ? 0 : 1;
}

int PtmCommands::Options::run_relight() const
{
    check_image_output(output);
    TextureDescription description = read_stex(input);
    if (!depends_on_light(description)) throw Error(input + ": model '" + description.model + "' does not depend on light");
    std::vector<Vec3> directions;
    for (const std::string& text : light_vectors) directions.push_back(parse_light_direction(text));
    for (const std::string& text : light_angles) directions.push_back(direction_from_angles(text));
    LightSet truth;
    if (!lights_from.empty()) {
        truth = read_light_set(lights_from);
        directions.insert(directions.end(), truth.directions.begin(), truth.directions.end());
    }
    if (directions.empty()) throw Error("relight: give at least one --light, --light-angles or --lights-from");
    if (compare && lights_from.empty()) throw Error("--compare: needs --lights-from (the truth images)");
    if (compare && directions.size() != truth.directions.size())
        throw Error("--compare: give the lights through --lights-from only");
    RenderSettings settings;
    settings.width = description.parameters.get<PtmParameters>().maps->width();
    settings.height = description.parameters.get<PtmParameters>().maps->height();
    if (!render_size.empty()) std::tie(settings.width, settings.height) = parse_size(render_size, "--size");
    settings.units_per_pixel = scale / description.pixels_per_unit;
    Image strip(settings.width * int(directions.size()), settings.height, 3);
    for (std::size_t i = 0; i < directions.size(); ++i) {
        set_light_direction(description, directions[i]);
        const Image lit = render(*make_texture(description), settings);
        paste(strip, lit, int(i) * settings.width, 0);
        if (!compare) continue;
        std::printf("light %zu (%s) vs %s:\n", i, angles_of(directions[i]).c_str(), fs::path(truth.images[i]).filename().c_str());
        print_comparison(read_image_linear(truth.images[i]), lit, pixelwise);
    }
    write_image(output, strip);
    std::printf("wrote %s (%zu light%s, %dx%d each)\n", output.c_str(), directions.size(), directions.size() > 1 ? "s" : "",
                settings.width, settings.height);
    return 0;
}

int PtmCommands::Options::run_export_maps() const
{
    if (normal_output.empty() && albedo_output.empty() && reference_normals.empty() && reference_albedo.empty())
        throw Error("export-maps: give --normal and/or --albedo (or a reference to measure against)");
    if (!normal_output.empty()) check_image_output(normal_output, "the normal map");
    if (!albedo_output.empty()) check_image_output(albedo_output, "the albedo map");
    const TextureDescription description = read_stex(input);
    if (!description.parameters.holds<PtmParameters>()) throw Error(input + ": not a ptm texture (model '" + description.model + "')");
    const SurfaceMaps maps = estimate_surface_maps(*description.parameters.get<PtmParameters>().maps, normal_estimator_from_string(estimator));
    if (!normal_output.empty()) write_normal_map(normal_output, maps.normals);
    if (!albedo_output.empty()) write_image(albedo_output, maps.albedo);
    if (!reference_normals.empty()) {
        // The reference is encoded as written: 0.5 + 0.5 n.
        Image truth = read_image_linear(reference_normals, {"linear"}, 1);
        for (float& v : truth.pixels) v = 2 * v - 1;
        const NormalErrors e = compare_normals(maps.normals, truth);
        std::printf("normal error (%s): mean %.2f°, median %.2f°, 90th percentile %.2f°\n", estimator.c_str(), e.mean,
                    e.median, e.percentile_90);
    }
    if (!reference_albedo.empty())
        std::printf("albedo error (%s): mean relative %.2f %%\n", estimator.c_str(),
                    100 * mean_relative_error(maps.albedo, read_image_linear(reference_albedo, {"linear"}, 1)));
    for (const std::string* path : {&normal_output, &albedo_output})
        if (!path->empty()) std::printf("wrote %s\n", path->c_str());
    return 0;
}

int PtmCommands::Options::run_relief() const
{
    const auto start = Clock::now();
    const ReliefSurface surface = make_relief_surface(height_map, downsample, depth);
    const std::array<int, 4> area = region.empty() ? std::array<int, 4>{0, 0, surface.width, surface.height} : parse_region(region);
    LightSet set;
    set.directions = lights_from.empty() ? spiral_light_directions(light_count, min_elevation, azimuth_offset)
                                         : read_light_set(lights_from).directions;
    fs::create_directories(output);
    auto progress = terminal_progress_bar();
    for (std::size_t i = 0; i < set.directions.size(); ++i) {
        if (progress) progress(double(i) / set.directions.size(), "relief");
        char name[32];
        std::snprintf(name, sizeof name, "light_%03zu.exr", i);
        const std::string path = (fs::path(output) / name).string();
        write_image(path, crop_periodic(shade_relief(surface, set.directions[i]), area[0], area[1], area[2], area[3]));
        set.images.push_back(path);
    }
    if (progress) progress(1.0, "relief");
    write_light_set((fs::path(output) / "lights.lp").string(), set);
    write_normal_map((fs::path(output) / "normal.exr").string(),
                     crop_periodic(relief_normals(surface), area[0], area[1], area[2], area[3]));
    write_image((fs::path(output) / "albedo.exr").string(), crop_periodic(surface.albedo, area[0], area[1], area[2], area[3]));
    std::printf("wrote %zu images of %dx%d texels, lights.lp, normal.exr and albedo.exr to %s in %.2f s\n",
                set.images.size(), area[2], area[3], output.c_str(), seconds_since(start));
    return 0;
}

int PtmCommands::Options::run_unbounded() const
{
    check_output_path(output, "the texture");
    const TextureDescription source = read_stex(input);
    PtmUnboundedOptions options;
    options.triangle_edge = triangle_edge;
    options.make_periodic = !already_periodic;
    options.seed = seed;
    TextureDescription description = make_unbounded_ptm(source, options);
    description.provenance.options.push_back({"unbounded", "triangle edge " + std::to_string(triangle_edge) + ", seed " +
                                                               std::to_string(seed) +
                                                               (already_periodic ? "" : ", periodic component")});
    write_stex(output, description);
    const PtmMaps& maps = *description.parameters.get<PtmParameters>().maps;
    std::printf("wrote %s: %dx%d texels of %s maps%s, tiled and blended over triangles of %.1f texels (seed %u)\n",
                output.c_str(), maps.width(), maps.height(), to_string(maps.colour),
                already_periodic ? "" : " (periodic component)", triangle_edge * std::min(maps.width(), maps.height()),
                unsigned(seed));
    return 0;
}

const CommandRegistration ptm_registration = register_command<PtmCommands>(HelpPosition::model_command, {"ptm"});

}  // namespace stex_cli
