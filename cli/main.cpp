// stex — the stochtex command-line tool. See `stex --help` and README.md.
#include "batch_command.h"
#include "bench_command.h"
#include "commands.h"
#include "progress_bar.h"
#include "ptm_commands.h"
#include "tiling_commands.h"

#include <stochtex/atomic_write.h>
#include <stochtex/error.h>

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <exception>

namespace {

// Every output is written to a temporary and renamed into place (stochtex/atomic_write.h), so
// an interrupted run never leaves a half-written file under an output's name; this handler
// removes the temporaries too, then dies of the signal so that the caller sees the interruption.
extern "C" void remove_outputs_and_die(int signal_number)
{
    stochtex::remove_pending_outputs();
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

void install_signal_handlers()
{
    struct sigaction action {};
    action.sa_handler = remove_outputs_and_die;
    sigemptyset(&action.sa_mask);
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal_number, &action, nullptr);
    // Past a file-size limit (ulimit -f) the default action kills the process, leaving the
    // temporary behind; ignored, the write fails with EFBIG and is reported like any other.
    std::signal(SIGXFSZ, SIG_IGN);
}

}  // namespace

int main(int argc, char** argv)
{
    using namespace stex_cli;
    CLI::App app{"stex — procedural textures by example (stochtex " STOCHTEX_VERSION ")"};
    // At most one sub-command; "none" is reported below, so that an unknown word is named as
    // such instead of as a missing sub-command.
    app.require_subcommand(0, 1);
    app.set_version_flag("--version", "stochtex " STOCHTEX_VERSION);
    bool progress_lines = false;
    app.add_flag("--progress-lines", progress_lines,
                 "Report progress as lines 'progress FRACTION STAGE' on stderr (for programs running stex)");

    AnalyzeCommand analyze;
    auto* a = app.add_subcommand("analyze", "Analyse a texture photo into a .stex procedural texture");
    a->add_option("photo", analyze.photo, "Photo of a stochastic texture (any format OpenImageIO reads)")->required();
    a->add_option("-o,--output", analyze.output, "Output .stex file")->required();
    // Models and their own options come from the registry: each model's declared options
    // (name, range, default, doc) become options here, and the core checks their values.
    a->add_option("--model", analyze.model, model_option_help())
        ->check(CLI::IsMember(analysable_models()))->capture_default_str();
    analyze.colour_option =
        a->add_option("--colour", analyze.colour,
                      "Colour mode: pca (decorrelated), rgb (independent), rgb-shared (with --model auto and no "
                      "--colour, each model is also tried in the other modes it declares: tiling in rgb)")
            ->check(CLI::IsMember({"pca", "rgb", "rgb-shared"}))
            ->capture_default_str();
    a->add_option("--histogram", analyze.histogram,
                  "Histogram matching: on, off, or auto (per channel, when it brings the histogram measurably closer)")
        ->check(CLI::IsMember({"auto", "on", "off"}))->capture_default_str();
    a->add_option("--joint-colour", analyze.joint_colour,
                  "Joint colour (pca colour; wavelet, gabor and lrp): on ties each chroma axis's value and spread to "
                  "brightness, as in the photo (independent channels make colours the photo never had: gravel's "
                  "false-colour rate 14.7 % -> 1.7 %); off keeps three independent channels, which POV-Ray's "
                  "procedural mode needs (stex pov bakes a joint-colour texture); auto: with --model auto each of "
                  "those models is fitted both ways and the scores decide, a named model is fitted without")
        ->check(CLI::IsMember({"auto", "on", "off"}))->capture_default_str();
    a->add_flag("--choice-structure", analyze.choice_structure,
                "With --model auto: score the candidates also by the structure distance (a seventh term of the "
                "fidelity penalty, target 0.25; docs/metrics.md, Structure). Off by default: it can change the choice");
    a->add_option("--knots", analyze.knots, "Knots of each histogram map")->check(CLI::Range(4, 64))->capture_default_str();
    a->add_option("--bands", analyze.bands, "Keep at most N finest bands (gabor: octaves) (0: all the photo supports)")
        ->check(CLI::Range(0, 24))->capture_default_str();
    analyze.add_model_options(*a);
    a->add_option("--seed", analyze.seed, "Seed stored in the texture")->capture_default_str();
    a->add_option("--colourspace,--colorspace", analyze.colour_space,
                  "Colour space of the photo's values (default: what the file says, else sRGB)");
    a->add_option("--unit-size", analyze.unit_size_m, "Physical width of the photo in metres (for scenes)")
        ->check(positive_number())->capture_default_str();

    RenderCommand render;
    auto* r = app.add_subcommand("render", "Render a .stex texture to an image (EXR: scene-linear; PNG/JPEG: sRGB)");
    r->add_option("texture", render.texture, ".stex file")->required();
    r->add_option("-o,--output", render.output, "Output image (.exr, .png, .jpg, .tif)")->required();
    r->add_option("--size", render.size, "Output size WxH (default: the analysed photo's size)");
    r->add_option("--scale", render.scale, "Exemplar pixels per output pixel (2: zoomed out ×2)")
        ->check(positive_number())->capture_default_str();
    r->add_option("--u", render.origin_u, "Texture-space u of the image's left edge (texture units)")->capture_default_str();
    r->add_option("--v", render.origin_v, "Texture-space v of the image's top edge (texture units)")->capture_default_str();
    r->add_flag("--solid", render.solid, "Evaluate the solid (3D) texture on the plane w = Z");
    r->add_option("--z", render.z, "Depth of the solid slice (texture units)")->capture_default_str();
    r->add_flag("--no-filter", render.no_filter, "Point-sample instead of filtering each pixel's footprint");
    r->add_flag("--tileable", render.tileable,
                "Make the image one period of the texture, so it tiles without a seam (band frequencies snap to fit)");
    r->add_option("--threads", render.threads, "Worker threads (0: all cores)")->check(non_negative_number())->capture_default_str();
    r->add_option("--seed", render.seed, "Override the texture's seed")->check(non_negative_number());

    InfoCommand info;
    auto* i = app.add_subcommand("info", "Print a .stex texture's parameters and statistics");
    i->add_option("texture", info.texture, ".stex file")->required();

    CompareCommand compare;
    auto* c = app.add_subcommand("compare", "Compare a photo with a texture: metrics, and a side-by-side figure");
    c->add_option("photo", compare.photo, "The photo")->required();
    c->add_option("texture", compare.texture, ".stex file")->required();
    c->add_option("-o,--output", compare.output, "Side-by-side PNG: photo, synthesis, their PSDs and histograms");
    c->add_option("--colourspace,--colorspace", compare.colour_space, "Colour space of the photo's values");

    MorphCommand morph;
    auto* m = app.add_subcommand("morph", "Interpolate two textures of the same model");
    m->add_option("a", morph.a, "Texture at t = 0")->required();
    m->add_option("b", morph.b, "Texture at t = 1")->required();
    m->add_option("--t", morph.t, "Interpolation parameter in [0, 1]")->check(CLI::Range(0.0, 1.0))->capture_default_str();
    m->add_option("-o,--output", morph.output, "Output .stex file")->required();

    BakeCommand bake;
    auto* b = app.add_subcommand("bake", "Bake a texture into a tiled, MIP-mapped EXR: one seamless period, each level filtered by the model");
    b->add_option("texture", bake.texture, ".stex file")->required();
    b->add_option("-o,--output", bake.output, "Output image (.exr)")->required();
    b->add_option("--size", bake.size, "Level-0 texels per side")->check(CLI::Range(8, 32768))->capture_default_str();
    b->add_option("--scale", bake.scale, "Exemplar pixels per texel (1: the photo's pixel scale)")
        ->check(positive_number())->capture_default_str();
    b->add_option("--tile", bake.tile, "Tile size (a power of two, 8 to 4096)")->capture_default_str();
    b->add_flag("--half", bake.half, "Store 16-bit half floats instead of 32-bit floats");
    b->add_option("--threads", bake.threads, "Worker threads (0: all cores)")->check(non_negative_number())->capture_default_str();
    b->add_option("--seed", bake.seed, "Override the texture's seed")->check(non_negative_number());
    b->add_option("--positions", bake.positions,
                  "Instead: the solid texture at the texels of this position map (RGBA float: xyz, alpha = covered), "
                  "e.g. a UV atlas of object coordinates baked by Blender");
    b->add_option("--position-scale", bake.position_scale, "With --positions: texture units per position unit")
        ->check(positive_number())->capture_default_str();

    OslCommand osl;
    auto* o = app.add_subcommand("osl", "Write an OSL shader with the texture's parameters built in (wavelet, gabor, tiling) and the images it reads");
    o->add_option("texture", osl.texture, ".stex file")->required();
    o->add_option("-o,--output", osl.output, "Output shader (.osl); the images it reads are written beside it (docs/osl.md)")->required();
    o->add_option("--name", osl.name, "Shader name (default: stochtex_ + the output file's name)");
    o->add_option("--tile-dir", osl.tile_dir, "Folder the shader names for the images it reads (default: the output's folder, absolute)");

    PovCommand pov;
    auto* p = app.add_subcommand("pov", "Write a POV-Ray 3.7 include: the texture as SDL (procedural) or a baked tileable EXR");
    p->add_option("texture", pov.texture, ".stex file")->required();
    p->add_option("-o,--output", pov.output, "Output include (.inc); baked mode also writes the image beside it (.exr)")->required();
    p->add_option("--name", pov.name, "Identifier prefix in the include (default: from the output file name)");
    p->add_option("--mode", pov.mode, "procedural (POV-Ray evaluates it: solid, unlimited) or baked (an image map; any model); "
                                      "default: procedural where the model allows it")
        ->check(CLI::IsMember({"procedural", "baked"}));
    p->add_option("--bake-size", pov.bake_size, "Baked mode: texels per side, 16 to 8192 (0: one texture unit at the photo's pixel scale, at most 2048)")
        ->check(CLI::Range(0, 8192))->capture_default_str();

    ModelsCommand models;
    auto* ml = app.add_subcommand("models", "List the texture models: what each is for, what it can do, its parameters");
    ml->add_flag("--json", models.json, "Machine-readable: the registry as JSON (name, summary, capabilities, parameters, options)");
    ml->add_flag("--markdown", models.markdown, "Each model's .stex parameter table, as in docs/stex-format.md");

    const BenchCommand bench(app);
    const PtmCommands ptm(app);
    const TilingCommands tiling(app);
    const BatchCommands batch(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    set_progress_lines(progress_lines);
    install_signal_handlers();
    if (app.get_subcommands().empty()) {
        std::fprintf(stderr, "stex: error: a sub-command is required (analyze, render, info, compare, morph, bake, osl, pov, models, bench, ptm, tiling, batch, batch-report); see stex --help\n");
        return 1;
    }
    try {
        if (*a) return analyze.run();
        if (*r) return render.run();
        if (*i) return info.run();
        if (*c) return compare.run();
        if (*m) return morph.run();
        if (*p) return pov.run();
        if (*b) return bake.run();
        if (*o) return osl.run();
        if (*ml) return models.run();
        if (bench.selected()) return bench.run();
        if (ptm.selected()) return ptm.run();
        if (tiling.selected()) return tiling.run();
        if (batch.selected()) return batch.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "stex: error: %s\n", e.what());
        return 1;
    }
    return 2;
}
