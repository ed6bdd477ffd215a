// `stex batch` and `stex batch-report` on this machine: outputs independent of --jobs, --threads
// and sharding, manifests with per-photo options, bad photos failing alone, --resume, --shard auto,
// progress lines, the gallery page. (On a real Slurm cluster and in a browser: tests/batch/.)
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using stochtex::test::contains;
using stochtex::test::ProgramResult;

std::string read_file(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_file(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

int count_of(const std::string& text, const std::string& part)
{
    int count = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
    return count;
}

/// Every file under `folder` but the shard logs and timings.csv (what varies from run to run),
/// relative path → bytes.
std::map<std::string, std::string> outputs_of(const fs::path& folder)
{
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (!entry.is_regular_file()) continue;
        const std::string relative = fs::relative(entry.path(), folder).string();
        if (relative.rfind("reports/", 0) == 0 || relative == "timings.csv") continue;
        files[relative] = read_file(entry.path());
    }
    return files;
}

class Batch : public ::testing::Test {
protected:
    void SetUp() override
    {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = stochtex::test::temp_dir(std::string("batch_") + info->name());
    }

    /// `count` photos (SIZE² variants of the committed exemplar) in dir/photos.
    fs::path make_photos(int count, int size = 96) const
    {
        const fs::path photos = dir / "photos";
        const ProgramResult r = stochtex::test::run_program(
            {"bash", STOCHTEX_SOURCE_DIR "/tests/batch/make_photos.sh", stochtex::test::repo_exemplar("concrete_512.png"),
             photos.string(), std::to_string(count), std::to_string(size)},
            dir.string());
        EXPECT_TRUE(r.succeeded()) << r;
        return photos;
    }

    ProgramResult stex(std::vector<std::string> args) const
    {
        args.insert(args.begin(), STOCHTEX_CLI);
        return stochtex::test::run_program(args, dir.string());
    }

    fs::path dir;
};

TEST_F(Batch, OutputsAreTheSameWhateverJobsThreadsAndShards)
{
    const fs::path photos = make_photos(4);
    const std::vector<std::string> options{"--compare", "--preview", "48"};
    const auto batch = [&](const std::string& out, std::vector<std::string> extra) {
        std::vector<std::string> args{"batch", photos.string(), "-o", (dir / out).string()};
        args.insert(args.end(), options.begin(), options.end());
        args.insert(args.end(), extra.begin(), extra.end());
        const ProgramResult r = stex(args);
        EXPECT_TRUE(r.succeeded()) << r;
    };
    batch("one", {"--jobs", "1", "--threads", "1"});
    batch("two", {"--jobs", "2", "--threads", "2"});
    for (const char* shard : {"2/3", "0/3", "1/3"}) batch("sharded", {"--shard", shard, "--threads", "2"});
    EXPECT_FALSE(fs::exists(dir / "sharded" / "report.json")) << "a shard merged on its own";
    const ProgramResult merged = stex({"batch-report", (dir / "sharded").string()});
    ASSERT_TRUE(merged.succeeded()) << merged;
    EXPECT_TRUE(contains(merged.out, "4 photos, 4 done, 0 failed, 0 missing")) << merged;

    const auto one = outputs_of(dir / "one");
    // 4 photos × (.stex, photo.png, synthesis.png, compare.png) + plan, report.json, report.csv, index.html
    EXPECT_EQ(one.size(), 4u * 4u + 4u);
    for (const char* other : {"two", "sharded"}) {
        const auto files = outputs_of(dir / other);
        ASSERT_EQ(files.size(), one.size()) << other;
        for (const auto& [name, bytes] : one) {
            ASSERT_TRUE(files.count(name)) << other << " lacks " << name;
            EXPECT_TRUE(files.at(name) == bytes) << name << " differs between --jobs 1 --threads 1 and " << other;
        }
    }
    // Each texture is exactly what `stex analyze` writes of the photo.
    const ProgramResult analyzed = stex({"analyze", (photos / "02_crop_c.png").string(), "-o", (dir / "alone.stex").string()});
    ASSERT_TRUE(analyzed.succeeded()) << analyzed;
    EXPECT_TRUE(read_file(dir / "alone.stex") == one.at("02_crop_c/02_crop_c.stex")) << "stex batch and stex analyze differ";
    // The choice is the analysis's own: the score table of `stex analyze --model auto`, kept in the report.
    const std::string report = read_file(dir / "one" / "report.json");
    EXPECT_EQ(count_of(report, "\"status\": \"done\""), 4) << report;
    EXPECT_GE(count_of(report, "\"penalty\""), 4 * 4) << "every candidate's penalty, and the chosen one's";
}

TEST_F(Batch, ManifestGivesPerPhotoOptionsAndBadPhotosFailAlone)
{
    const fs::path photos = make_photos(2);
    write_file(photos / "garbage.png", "not a PNG at all");
    write_file(photos / "manifest.csv",
               "photo,name,model,colour,unit_size\n"
               "00_crop_a.png,first,wavelet,rgb,\n"
               "01_crop_b.png,,gabor,,2.5\n"
               "missing.png,,,,\n"
               "garbage.png,,,,\n"
               "00_crop_a.png,unknown_model,nonsense,,\n"
               "\"00_crop_a.png\",\"bad, unit\",wavelet,,banana\n");
    const ProgramResult r = stex({"batch", (photos / "manifest.csv").string(), "-o", (dir / "out").string(), "--preview", "0"});
    ASSERT_TRUE(r.exited) << r;
    EXPECT_EQ(r.code, 4) << "the exit status is the number of failed photos\n" << r;
    const std::string csv = read_file(dir / "out" / "report.csv");
    EXPECT_EQ(count_of(csv, "\n"), 7) << csv;  // the header and six photos
    EXPECT_TRUE(contains(csv, "0,first,00_crop_a.png,done,wavelet,rgb,96,96,")) << csv;
    EXPECT_TRUE(contains(csv, "1,01_crop_b,01_crop_b.png,done,gabor,pca")) << csv;
    EXPECT_TRUE(contains(csv, "2,missing,missing.png,failed")) << csv;
    EXPECT_TRUE(contains(csv, "3,garbage,garbage.png,failed")) << csv;
    EXPECT_TRUE(contains(csv, "model 'nonsense' is not one that analyses photos")) << csv;
    EXPECT_TRUE(contains(csv, "5,bad__unit,00_crop_a.png,failed")) << csv;
    EXPECT_TRUE(contains(csv, "unit_size: expected a number > 0")) << csv;
    const std::string report = read_file(dir / "out" / "report.json");
    EXPECT_TRUE(contains(report, "missing.png")) << "a failed photo's message names its file\n" << report;
    EXPECT_TRUE(contains(r.out, "failed missing (missing.png): ")) << r;
    const std::string second = read_file(dir / "out" / "01_crop_b" / "01_crop_b.stex");
    EXPECT_TRUE(contains(second, "\"unit_size_m\": 2.5")) << "the manifest's unit size";
}

TEST_F(Batch, JsonManifestAndSourcesThatCannotStart)
{
    const fs::path photos = make_photos(2);
    write_file(photos / "list.json",
               R"({"photos": [{"photo": "00_crop_a.png", "name": "a", "model": "wavelet"}, "01_crop_b.png"]})");
    const ProgramResult ok = stex({"batch", (photos / "list.json").string(), "-o", (dir / "json").string(), "--model", "wavelet"});
    EXPECT_TRUE(ok.succeeded()) << ok;
    EXPECT_TRUE(fs::exists(dir / "json" / "a" / "a.stex"));
    EXPECT_TRUE(fs::exists(dir / "json" / "01_crop_b" / "01_crop_b.stex"));

    const auto cannot_start = [&](const std::string& source, const std::string& message) {
        const ProgramResult r = stex({"batch", source, "-o", (dir / "never").string()});
        ASSERT_TRUE(r.exited) << r;
        EXPECT_EQ(r.code, 1) << r;
        EXPECT_TRUE(contains(r.err, source)) << "the message names the source\n" << r;
        EXPECT_TRUE(contains(r.err, message)) << r;
    };
    write_file(photos / "broken.json", "[{\"photo\": ");
    cannot_start((photos / "broken.json").string(), "not valid JSON");
    write_file(photos / "twice.csv", "photo\n00_crop_a.png\nsub/00_crop_a.png\n");
    cannot_start((photos / "twice.csv").string(), "have one output name '00_crop_a'");
    write_file(photos / "nocolumn.csv", "file\n00_crop_a.png\n");
    cannot_start((photos / "nocolumn.csv").string(), "no 'photo' column");
    cannot_start((dir / "no_such_folder").string(), "no such folder or manifest");
    EXPECT_FALSE(fs::exists(dir / "never" / "report.json"));
}

TEST_F(Batch, ResumeSkipsFinishedPhotosAndDoesNoneTwice)
{
    const fs::path photos = make_photos(3);
    const std::string out = (dir / "out").string();
    const ProgramResult first = stex({"batch", photos.string(), "-o", out, "--model", "wavelet", "--shard", "0/2"});
    ASSERT_TRUE(first.succeeded()) << first;
    EXPECT_TRUE(contains(first.out, "merge the shards with: stex batch-report")) << first;
    // What a killed run (SIGKILL: no handler runs) leaves of a photo in flight: a temporary.
    const fs::path stale = dir / "out" / "01_crop_b" / "01_crop_b.stex.4242-0.tmp";
    fs::create_directories(stale.parent_path());
    write_file(stale, "half a texture");
    const ProgramResult rest = stex({"batch", photos.string(), "-o", out, "--model", "wavelet", "--resume"});
    ASSERT_TRUE(rest.succeeded()) << rest;
    EXPECT_TRUE(contains(rest.out, "1 to convert (2 done before, skipped)")) << rest;
    EXPECT_TRUE(contains(rest.out, "3 photos, 3 done, 0 failed, 0 missing")) << rest;
    EXPECT_FALSE(fs::exists(stale)) << "the stale temporary of the photo converted again";
    const ProgramResult again = stex({"batch", photos.string(), "-o", out, "--model", "wavelet", "--resume"});
    ASSERT_TRUE(again.succeeded()) << again;
    EXPECT_TRUE(contains(again.out, "0 to convert (3 done before, skipped)")) << again;
    std::string logs;
    for (const auto& entry : fs::directory_iterator(dir / "out" / "reports")) logs += read_file(entry.path());
    for (const char* name : {"00_crop_a", "01_crop_b", "02_crop_c"})
        EXPECT_EQ(count_of(logs, std::string("\"name\":\"") + name + "\""), 1) << name << " done more than once:\n" << logs;

    // Another batch into the same folder is refused: its reports would mix.
    const fs::path other = dir / "other";
    fs::create_directories(other);
    fs::copy_file(photos / "00_crop_a.png", other / "x.png");
    const ProgramResult mixed = stex({"batch", other.string(), "-o", out, "--resume"});
    EXPECT_EQ(mixed.code, 1) << mixed;
    EXPECT_TRUE(contains(mixed.err, "holds another batch")) << mixed;
}

TEST_F(Batch, ShardAutoReadsTheSlurmArrayVariables)
{
    const fs::path photos = make_photos(3);
    using stochtex::test::shell_quote;
    const std::string command = std::string("SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 ") + shell_quote(STOCHTEX_CLI) +
                                " batch " + shell_quote(photos.string()) + " -o " + shell_quote((dir / "out").string()) +
                                " --model wavelet --preview 0 --shard auto";
    const auto r = stochtex::test::run_command(command);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "shard-1-of-2: 1 to convert")) << r.output;
    EXPECT_TRUE(fs::exists(dir / "out" / "01_crop_b" / "01_crop_b.stex"));
    EXPECT_FALSE(fs::exists(dir / "out" / "00_crop_a"));

    const auto r2 = stochtex::test::run_command("env -u SLURM_ARRAY_TASK_ID " + shell_quote(STOCHTEX_CLI) + " batch " +
                                                shell_quote(photos.string()) + " -o " + shell_quote((dir / "o2").string()) +
                                                " --shard auto");
    EXPECT_EQ(r2.status, 1) << r2.output;
    EXPECT_TRUE(contains(r2.output, "SLURM_ARRAY_TASK_ID=unset")) << r2.output;
    const ProgramResult bad = stex({"batch", photos.string(), "-o", (dir / "o3").string(), "--shard", "2/2"});
    EXPECT_EQ(bad.code, 1) << bad;
    EXPECT_TRUE(contains(bad.err, "--shard: '2/2': expected 0 <= I < N")) << bad;
}

TEST_F(Batch, ProgressLinesAndGallery)
{
    const fs::path photos = make_photos(2);
    const ProgramResult r =
        stex({"batch", photos.string(), "-o", (dir / "out").string(), "--model", "wavelet", "--progress-lines"});
    ASSERT_TRUE(r.succeeded()) << r;
    EXPECT_TRUE(contains(r.err, "progress 0.5000 batch 1/2 eta ")) << r;
    EXPECT_TRUE(contains(r.err, "progress 1.0000 batch 2/2 eta 0")) << r;
    const std::string html = read_file(dir / "out" / "index.html");
    EXPECT_EQ(count_of(html, "<img src=\""), 4) << html;
    EXPECT_TRUE(contains(html, "href=\"00_crop_a/00_crop_a.stex\"")) << html;
    EXPECT_TRUE(contains(html, "src=\"01_crop_b/synthesis.png\"")) << html;
    EXPECT_FALSE(contains(html, "http:") || contains(html, "https:") || contains(html, "//cdn")) << "no external assets";
}

}  // namespace
