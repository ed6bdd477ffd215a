#include "batch_command.h"

#include "batch_inputs.h"
#include "batch_progress.h"
#include "batch_report.h"
#include "batch_shard.h"
#include "commands.h"
#include "compare_figure.h"
#include "progress_bar.h"

#include <stochtex/analysis.h>
#include <stochtex/bake.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/stex_file.h>

#include <tbb/task_arena.h>

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>

namespace stex_cli {

using namespace stochtex;
namespace fs = std::filesystem;

struct BatchCommands::Options {
    CLI::App *batch = nullptr, *report = nullptr;
    std::string source, output, shard;
    int jobs = 1, threads = 0, preview = 128, bake = 0;
    bool resume = false, merge = false, compare = false, progress_lines = false;
    // The analysis's options, as `stex analyze` has them; a manifest may set model, colour and
    // unit size per photo.
    std::string model = automatic_model, colour, joint_colour = "auto";
    std::uint32_t seed = 1;
    double unit_size_m = 1.0;
};

BatchCommands::BatchCommands(CLI::App& app) : options_(std::make_unique<Options>())
{
    Options& o = *options_;
    o.batch = app.add_subcommand("batch", "Convert a texture library: analyse every photo of a folder or manifest "
                                          "(sharded, resumable), with a report and an index.html gallery");
    o.batch->add_option("source", o.source,
                        "Folder of photos (its image files, by name) or manifest: .csv with a header row (photo, and "
                        "optionally name, model, colour, unit_size) or .json (an array of such objects); the order is "
                        "the photos' stable index");
    o.batch->add_option("-o,--output", o.output, "Output folder: <name>/<name>.stex per photo, report.json, report.csv, index.html")
        ->required();
    o.batch->add_option("--jobs", o.jobs, "Photos analysed side by side on this machine")->check(CLI::Range(1, 256))->capture_default_str();
    o.batch->add_option("--threads", o.threads,
                        "Threads per photo (0: the cores this process may use, divided by --jobs, at least 1); the "
                        "outputs do not depend on it")
        ->check(CLI::Range(0, 1024))->capture_default_str();
    o.batch->add_option("--shard", o.shard,
                        "I/N: convert only the photos whose stable index mod N is I (one task of an array job); auto: "
                        "I and N from SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT. Without it the whole batch runs "
                        "and the report is merged at the end; with it, merge with stex batch-report");
    o.batch->add_flag("--resume", o.resume, "Skip the photos a report of this output folder has as done (outputs are written atomically, so they are complete)");
    o.batch->add_flag("--merge", o.merge, "Only merge the shards' reports of the output folder (as stex batch-report)");
    o.batch->add_option("--model", o.model, "Model of every photo a manifest gives none (auto: as stex analyze)")
        ->check(CLI::IsMember(analysable_models()))->capture_default_str();
    o.batch->add_option("--colour,--color", o.colour, "Colour mode of every photo a manifest gives none (default: as stex analyze without --colour)")
        ->check(CLI::IsMember({"pca", "rgb", "rgb-shared"}));
    o.batch->add_option("--joint-colour", o.joint_colour, "As stex analyze --joint-colour")
        ->check(CLI::IsMember({"auto", "on", "off"}))->capture_default_str();
    o.batch->add_option("--seed", o.seed, "Seed stored in every texture")->capture_default_str();
    o.batch->add_option("--unit-size", o.unit_size_m, "Physical width of a photo in metres, where a manifest gives none")
        ->check(positive_number())->capture_default_str();
    o.batch->add_option("--preview", o.preview,
                        "Side of the photo.png and synthesis.png crops the gallery shows, at the photo's pixel scale (0: none)")
        ->check(CLI::Range(0, 4096))->capture_default_str();
    o.batch->add_flag("--compare", o.compare, "Also write each photo's compare.png figure (as stex compare -o)");
    o.batch->add_option("--bake", o.bake, "Also bake each texture into <name>.exr, SIZE texels a side (as stex bake --size; 0: no bake)")
        ->check(CLI::Range(0, 0) | CLI::Range(8, 32768))->capture_default_str();

    o.batch->add_flag("--progress-lines", o.progress_lines,
                      "Progress as lines 'progress FRACTION batch DONE/TOTAL eta SECONDS' on stderr, for programs "
                      "(as stex --progress-lines batch)");

    o.report = app.add_subcommand("batch-report", "Merge the shards' reports of a stex batch output folder into report.json, "
                                                  "report.csv, timings.csv and index.html");
    o.report->add_option("folder", o.output, "The batch's output folder")->required();
}

BatchCommands::~BatchCommands() = default;

bool BatchCommands::selected() const { return *options_->batch || *options_->report; }

namespace {

/// The cores this process may run on (a scheduler's CPU set, taskset), not the machine's.
int usable_cores()
{
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
    return int(std::max(1u, std::thread::hardware_concurrency()));
}

int exit_status(int failed) { return std::min(failed, 100); }

int merge_and_tell(const std::string& folder)
{
    const MergeSummary s = merge_batch_reports(folder);
    std::printf("merged %s: %d photos, %d done, %d failed, %d missing -> report.json, report.csv, timings.csv, index.html\n",
                folder.c_str(), s.total, s.done, s.failed, s.missing);
    return exit_status(s.failed + s.missing);
}

/// A top-left crop of at most side×side pixels.
Image crop(const Image& image, int side)
{
    const int w = std::min(image.width, side), h = std::min(image.height, side);
    Image out(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = image.at(x, y, c);
    return out;
}

/// Temporaries a killed run left in a photo's folder (SIGKILL leaves no time to remove them; see
/// stochtex/atomic_write.h). The folder is this photo's alone, and only the one task converting
/// the photo writes there, so whatever .tmp file it holds is stale.
void remove_stale_temporaries(const fs::path& folder)
{
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
        if (entry.path().extension() == ".tmp") fs::remove(entry.path());
}

/// One photo: its analysis and the outputs asked for, each written atomically; a failure is the
/// record's, never the batch's.
PhotoRecord convert_photo(const BatchPhoto& photo, const BatchCommands::Options& o, int threads)
{
    const auto start = std::chrono::steady_clock::now();
    PhotoRecord record;
    record.index = photo.index;
    record.name = photo.name;
    record.photo = photo.listed_as;
    try {
        const std::string model = photo.model.empty() ? o.model : photo.model;
        const std::vector<std::string> models = analysable_models();
        if (std::find(models.begin(), models.end(), model) == models.end())
            throw Error("model '" + model + "' is not one that analyses photos (stex models)");
        const std::string colour = photo.colour.empty() ? o.colour : photo.colour;
        if (photo.unit_size_m < 0) throw Error("unit_size: expected a number > 0 (metres)");
        const fs::path folder = fs::path(o.output) / photo.name;
        fs::create_directories(folder);
        remove_stale_temporaries(folder);
        const Image image = read_image_linear(photo.path);
        record.width = image.width;
        record.height = image.height;

        AnalysisOptions options;
        options.model = model;
        options.colour_mode = colour_mode_from_string(colour.empty() ? "pca" : colour);
        options.try_colour_modes = colour.empty();
        options.joint_colour = o.joint_colour == "on";
        options.try_joint_colour = o.joint_colour == "auto";
        options.seed = o.seed;
        options.unit_size_m = photo.unit_size_m > 0 ? photo.unit_size_m : o.unit_size_m;
        options.source_name = fs::path(photo.path).filename().string();
        options.input_colour_space = "file";
        const TextureDescription description = analyze(image, options);
        const auto output = [&](const std::string& file) {
            record.outputs.push_back(photo.name + "/" + file);
            return (folder / file).string();
        };
        const std::string stex = output(photo.name + ".stex");
        write_stex(stex, description);
        record.bytes = (long long)fs::file_size(stex);
        fill_from_description(record, description);
        if (o.preview > 0) {
            const Image photo_crop = crop(image, o.preview);
            write_image(output("photo.png"), photo_crop);
            write_image(output("synthesis.png"),
                        render_at_photo_scale(description, photo_crop.width, photo_crop.height, threads));
        }
        if (o.compare) {
            const Image synthesis = render_at_photo_scale(description, image.width, image.height, threads);
            write_image(output("compare.png"),
                        compare_figure(image, synthesis, compare_images(image, synthesis),
                                       fs::path(photo.path).filename().string(),
                                       photo.name + ".stex (" + description.model + ")")
                            .image);
        }
        if (o.bake > 0) {
            BakeOptions bake;
            bake.width = bake.height = o.bake;
            bake.threads = threads;
            bake_mip_image(description, output(photo.name + ".exr"), bake);
        }
        record.status = "done";
    } catch (const std::exception& e) {
        record.status = "failed";
        record.error = e.what();
        record.outputs.clear();
    }
    record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return record;
}

std::string photo_line(const PhotoRecord& r)
{
    char line[512];
    if (r.status != "done") {
        std::snprintf(line, sizeof line, "failed %s (%s): %s", r.name.c_str(), r.photo.c_str(), r.error.c_str());
        return line;
    }
    if (r.chosen >= 0)
        std::snprintf(line, sizeof line, "done   %s: %s (%s), penalty %.3f, %lld bytes, %.1f s", r.name.c_str(),
                      r.model.c_str(), r.colour.c_str(), r.candidates[r.chosen].penalty, r.bytes, r.seconds);
    else
        std::snprintf(line, sizeof line, "done   %s: %s (%s), %lld bytes, %.1f s", r.name.c_str(), r.model.c_str(),
                      r.colour.c_str(), r.bytes, r.seconds);
    return line;
}

}  // namespace

int BatchCommands::run() const
{
    const Options& o = *options_;
    if (*o.report || o.merge) return merge_and_tell(o.output);
    if (o.source.empty()) throw Error("batch: a folder or manifest of photos is needed (or --merge)");

    if (o.progress_lines) set_progress_lines(true);
    const std::vector<BatchPhoto> photos = list_batch_photos(o.source);
    const BatchShard shard = o.shard.empty() ? BatchShard{} : parse_batch_shard(o.shard, [](const char* name) { return std::getenv(name); });
    std::error_code error;
    fs::create_directories(fs::path(o.output) / "reports", error);
    if (error) throw Error(o.output + ": cannot create the output folder: " + error.message());
    write_batch_plan(o.output, photos);
    const std::string log = shard_log_path(o.output, shard.label());
    if (!o.resume) fs::remove(log);  // a fresh run of this shard: its earlier records are redone

    std::set<std::string> finished;
    if (o.resume)
        for (const std::string& name : finished_names(o.output)) finished.insert(name);
    std::vector<const BatchPhoto*> todo;
    int skipped = 0;
    for (const BatchPhoto& photo : photos) {
        if (!shard.holds(photo.index)) continue;
        if (finished.count(photo.name)) ++skipped;
        else todo.push_back(&photo);
    }
    const int jobs = std::max(1, std::min(o.jobs, int(todo.size())));
    // Each photo's analysis fills its threads itself; --jobs photos side by side share the cores.
    const int threads = o.threads > 0 ? o.threads : std::max(1, usable_cores() / jobs);
    std::printf("batch %s: %zu photos, %s: %zu to convert%s, %d at a time, %d thread%s each\n", o.source.c_str(),
                photos.size(), shard.label().c_str(), todo.size(),
                skipped ? (" (" + std::to_string(skipped) + " done before, skipped)").c_str() : "", jobs, threads,
                threads == 1 ? "" : "s");
    std::fflush(stdout);

    BatchProgress progress(int(todo.size()));
    std::atomic<std::size_t> next{0};
    std::atomic<int> failed{0};
    std::exception_ptr batch_error;  // a report that cannot be written stops the batch (every worker)
    std::mutex batch_error_mutex;
    const auto work = [&] {
        tbb::task_arena arena(threads);  // this photo's threads: the analysis's parallel loops stay within them
        for (std::size_t i; (i = next++) < todo.size();) {
            const PhotoRecord record = arena.execute([&] { return convert_photo(*todo[i], o, threads); });
            try {
                append_record(log, record);  // after every output: a record is a finished photo
            } catch (...) {
                const std::lock_guard<std::mutex> lock(batch_error_mutex);
                if (!batch_error) batch_error = std::current_exception();
                next = todo.size();
                return;
            }
            failed += record.status != "done";
            progress.photo_finished(record.status != "done", photo_line(record));
        }
    };
    std::vector<std::thread> workers;
    for (int j = 1; j < jobs; ++j) workers.emplace_back(work);
    work();
    for (std::thread& worker : workers) worker.join();
    if (batch_error) std::rethrow_exception(batch_error);

    if (o.shard.empty()) return std::max(exit_status(failed), merge_and_tell(o.output));
    std::printf("%s: %zu converted, %d failed; merge the shards with: stex batch-report %s\n", shard.label().c_str(),
                todo.size(), int(failed), o.output.c_str());
    return exit_status(failed);
}

const CommandRegistration batch_registration = register_command<BatchCommands>(HelpPosition::batch, {"batch", "batch-report"});

}  // namespace stex_cli
