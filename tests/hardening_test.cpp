// Regression tests for issue 16's findings (crashes, undefined behaviour, silent wrong output,
// destroyed outputs, unbounded reads). Every input is made here from the committed exemplar
// data/exemplars/concrete_512.png, never stored: each test says how its reproducer is built.
#include "test_support.h"

#include "models/ptm/ptm_coefficient_file.h"

#include <stochtex/analysis.h>
#include <stochtex/bake.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/mip_image.h>
#include <stochtex/models/ptm.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <signal.h>
#include <sys/resource.h>

namespace fs = std::filesystem;
using stochtex::test::contains;

namespace {

const stochtex::Image& exemplar()
{
    static const stochtex::Image image = stochtex::read_image_linear(stochtex::test::repo_exemplar("concrete_512.png"));
    return image;
}

/// The exemplar's top-left size² pixels.
stochtex::Image crop(int size)
{
    stochtex::Image out(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = exemplar().at(x, y, c);
    return out;
}

/// The issue's low-contrast grey photo: the top-left 256² in grey (Rec.709 luma), its contrast
/// scaled by `contrast` around its mean.
stochtex::Image low_contrast_grey(double contrast)
{
    stochtex::Image grey = crop(256);
    double mean = 0;
    std::vector<double> luma(grey.pixel_count());
    for (std::size_t i = 0; i < luma.size(); ++i) {
        const float* p = &grey.pixels[3 * i];
        luma[i] = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        mean += luma[i] / double(luma.size());
    }
    for (std::size_t i = 0; i < luma.size(); ++i)
        for (int c = 0; c < 3; ++c) grey.pixels[3 * i + c] = float(mean + contrast * (luma[i] - mean));
    return grey;
}

stochtex::Image scaled(stochtex::Image image, double factor)
{
    for (float& v : image.pixels) v = float(v * factor);
    return image;
}

stochtex::TextureDescription analysed(const std::string& model)
{
    stochtex::AnalysisOptions options;
    options.model = model;
    return stochtex::analyze(exemplar(), options);
}

using stochtex::test::error_of;

std::string read_bytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Files in `dir` other than the runner's stdout/stderr captures.
std::vector<std::string> files_in(const fs::path& dir)
{
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name != "stdout.txt" && name != "stderr.txt") names.push_back(name);
    }
    std::sort(names.begin(), names.end());
    return names;
}

stochtex::test::ProgramResult run_stex(const std::vector<std::string>& args, const fs::path& dir)
{
    std::vector<std::string> argv{STOCHTEX_CLI};
    argv.insert(argv.end(), args.begin(), args.end());
    return stochtex::test::run_program(argv, dir.string());
}

void expect_clean_error(const stochtex::test::ProgramResult& r, const std::string& name)
{
    ASSERT_TRUE(r.exited) << r;
    EXPECT_EQ(r.code, 1) << r;
    EXPECT_TRUE(contains(r.err, "stex: error:")) << r;
    EXPECT_TRUE(contains(r.err, name)) << "stderr does not name '" << name << "'\n" << r;
    EXPECT_FALSE(contains(r.out, "wrote")) << r;
}

// ---- Analysis: crashes on unusual photos ------------------------------------------------------

// Was a SIGSEGV: the non-negative least squares of the leakage correction freed every column and
// asked Eigen to factor a matrix with none.
TEST(Hardening, LrpFitsALowContrastGreyPhoto)
{
    stochtex::AnalysisOptions options;
    options.model = "lrp";
    const stochtex::TextureDescription description = stochtex::analyze(low_contrast_grey(0.25), options);
    EXPECT_NO_THROW(stochtex::validate(description, "low-contrast grey"));
    stochtex::RenderSettings settings;
    settings.width = settings.height = 32;
    settings.units_per_pixel = 1.0 / description.pixels_per_unit;
    const stochtex::Image image = stochtex::render(*stochtex::make_texture(description), settings);
    for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v));
}

// Was a SIGSEGV in the Gabor fit (no finite residual, so no best fit) and an invalid lrp
// description (turbulence NaN); now the photo is rejected up front, naming it and the limit.
TEST(Hardening, VeryBrightPhotoIsRejectedWithTheLimit)
{
    const stochtex::Image bright = scaled(crop(256), 1e18);
    for (const char* model : {"gabor", "lrp", "wavelet"}) {
        stochtex::AnalysisOptions options;
        options.model = model;
        options.source_name = "bright.exr";
        const std::string message = error_of([&] { stochtex::analyze(bright, options); });
        EXPECT_TRUE(contains(message, "bright.exr") && contains(message, "1e10")) << model << ": " << message;
    }
}

// Within the analysis limit but beyond what an lrp .stex stores: a clear error, not a failed
// validation of a coefficient step the user never chose.
TEST(Hardening, LrpNamesTheCoefficientRangeForBrightPhotos)
{
    stochtex::AnalysisOptions options;
    options.model = "lrp";
    const std::string message = error_of([&] { stochtex::analyze(scaled(crop(256), 1e6), options); });
    EXPECT_TRUE(contains(message, "lrp") && contains(message, "structure coefficients")) << message;
}

// ---- Positions, scales and periods at the API boundary ------------------------------------------

TEST(Hardening, RenderRejectsNonFiniteAndFarPositions)
{
    for (const char* model : {"wavelet", "lrp"}) {
        const auto texture = stochtex::make_texture(analysed(model));
        auto settings_with = [&](auto change) {
            stochtex::RenderSettings settings;
            settings.width = settings.height = 8;
            change(settings);
            return settings;
        };
        const std::vector<std::pair<std::string, stochtex::RenderSettings>> bad{
            {"origin_u", settings_with([](auto& s) { s.origin_u = NAN; })},
            {"origin_u", settings_with([](auto& s) { s.origin_u = 1e18; })},
            {"origin_u", settings_with([](auto& s) { s.origin_u = 1e30; })},
            {"origin_v", settings_with([](auto& s) { s.origin_v = NAN; })},
            {"z", settings_with([](auto& s) { s.solid = true, s.z = NAN; })},
            {"right edge", settings_with([](auto& s) { s.units_per_pixel = 1e30; })},
        };
        for (const auto& [name, settings] : bad) {
            const stochtex::RenderSettings& given = settings;  // a lambda cannot capture a binding (C++17)
            const std::string message = error_of([&] { stochtex::render(*texture, given); });
            EXPECT_TRUE(contains(message, name)) << model << ": expected an error naming " << name << ", got '" << message << "'";
        }
        // Far but inside the bound: rendered, finite.
        const stochtex::Image far = stochtex::render(*texture, settings_with([](auto& s) { s.origin_u = 1e6; }));
        for (float v : far.pixels) ASSERT_TRUE(std::isfinite(v)) << model;
    }
}

// The wavelet's periodic lattice counted tiles in an int (signed overflow for periods past
// 2^31 lattice cells); such periods are allowed up to the position bound and now work.
TEST(Hardening, PeriodicTexturesAcceptHugeInRangePeriodsAndRejectLarger)
{
    const stochtex::TextureDescription description = analysed("wavelet");
    const double largest = stochtex::max_position_pixels / description.pixels_per_unit;
    const auto periodic = stochtex::make_periodic_texture(description, {largest / 2, 1.0});
    stochtex::RenderSettings settings;
    settings.width = settings.height = 8;
    settings.units_per_pixel = 1.0 / description.pixels_per_unit;
    for (float v : stochtex::render(*periodic, settings).pixels) ASSERT_TRUE(std::isfinite(v));
    EXPECT_TRUE(contains(error_of([&] { stochtex::make_periodic_texture(description, {1e30, 1.0}); }), "period"));

    // The plugin's stex:scale 1e38 reaches MipImage as the layout's scale.
    stochtex::ImageLayout layout;
    layout.scale = 1e38;
    EXPECT_TRUE(contains(error_of([&] { stochtex::MipImage(description, layout, "t.stex"); }), "image.scale"));

    const std::string dir = stochtex::test::temp_dir("HugeBakeScale");
    stochtex::BakeOptions options;
    options.width = options.height = 64;
    options.scale = 1e30;
    const std::string out = dir + "/b.exr";
    EXPECT_TRUE(contains(error_of([&] { stochtex::bake_mip_image(description, out, options); }), "scale"));
    EXPECT_FALSE(fs::exists(out));
}

TEST(HardeningCli, RenderAndBakeRejectBadCoordinatesNamingTheOption)
{
    const fs::path dir = stochtex::test::temp_dir("BadCoordinates");
    const std::string photo = stochtex::test::repo_exemplar("concrete_512.png");
    ASSERT_TRUE(run_stex({"analyze", photo, "-o", (dir / "w.stex").string(), "--model", "wavelet"}, dir).succeeded());
    ASSERT_TRUE(run_stex({"analyze", photo, "-o", (dir / "l.stex").string(), "--model", "lrp"}, dir).succeeded());
    const std::string out = (dir / "o.exr").string();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"render", (dir / "w.stex").string(), "--u", "nan"}, "--u"},
        {{"render", (dir / "w.stex").string(), "--v", "nan"}, "--v"},
        {{"render", (dir / "w.stex").string(), "--solid", "--z", "nan"}, "--z"},
        {{"render", (dir / "w.stex").string(), "--u", "1e18"}, "--u"},
        {{"render", (dir / "l.stex").string(), "--u", "nan"}, "--u"},
        {{"render", (dir / "l.stex").string(), "--u", "1e30"}, "--u"},
        {{"render", (dir / "l.stex").string(), "--scale", "1e30"}, "--scale"},
        {{"render", (dir / "w.stex").string(), "--tileable", "--scale", "1e30"}, "--scale"},
        {{"render", (dir / "w.stex").string(), "--scale", "nan"}, "--scale"},
        {{"bake", (dir / "w.stex").string(), "--size", "64", "--scale", "1e13"}, "--scale"},
    };
    for (auto [args, name] : cases) {
        args.insert(args.end(), {"--size", "16x16", "-o", out});
        if (args[0] == "bake") args.erase(args.end() - 4, args.end() - 2);  // bake's --size is N
        const auto r = run_stex(args, dir);
        ASSERT_TRUE(r.exited) << r;
        EXPECT_NE(r.code, 0) << r;
        EXPECT_TRUE(contains(r.err, name)) << r;
        EXPECT_FALSE(fs::exists(out)) << r;
    }
    // Was signed overflow in the wavelet's periodic lattice: a huge but in-range scale (every
    // band filtered away, so the bake is the texture's mean) bakes with finite values.
    const auto baked = run_stex({"bake", (dir / "w.stex").string(), "--size", "64", "--scale", "1e10", "-o", out}, dir);
    ASSERT_TRUE(baked.succeeded()) << baked;
    const stochtex::Image map = stochtex::read_image_linear(out);
    for (float v : map.pixels) ASSERT_TRUE(std::isfinite(v));
    fs::remove(out);

    // Ranges are printed readably: no 309-digit DBL_MAX.
    const auto r = run_stex({"render", (dir / "w.stex").string(), "-o", out, "--scale", "-1"}, dir);
    EXPECT_NE(r.code, 0) << r;
    EXPECT_TRUE(contains(r.err, "--scale")) << r;
    EXPECT_FALSE(contains(r.err, "179769313")) << r;
}

// ---- Safe writes ------------------------------------------------------------------------------

// A write that fails part-way (here: past a file-size limit) keeps the previous file and leaves
// no temporary; "wrote" is not printed.
TEST(HardeningCli, FailedWriteKeepsThePreviousOutput)
{
    const fs::path dir = stochtex::test::temp_dir("FailedWrite");
    const std::string photo = stochtex::test::repo_exemplar("concrete_512.png");
    const std::string texture = (dir / "w.stex").string();
    ASSERT_TRUE(run_stex({"analyze", photo, "-o", texture, "--model", "wavelet"}, dir).succeeded());
    for (const char* name : {"old.exr", "old.png"}) {
        const std::string out = (dir / name).string();
        ASSERT_TRUE(run_stex({"render", texture, "-o", out, "--size", "16x16"}, dir).succeeded());
        const std::string before = read_bytes(out);
        const std::vector<std::string> files = files_in(dir);
        // The limit is inherited by the child; the captures of its output stay far below it.
        rlimit old_limit{};
        getrlimit(RLIMIT_FSIZE, &old_limit);
        rlimit limit = old_limit;
        limit.rlim_cur = 64 * 1024;
        signal(SIGXFSZ, SIG_IGN);
        setrlimit(RLIMIT_FSIZE, &limit);
        const auto r = run_stex({"render", texture, "-o", out, "--size", "1024x1024"}, dir);
        setrlimit(RLIMIT_FSIZE, &old_limit);
        expect_clean_error(r, name);
        EXPECT_TRUE(read_bytes(out) == before) << name << " was changed";
        EXPECT_EQ(files_in(dir), files) << "a temporary was left behind";
    }
    // A folder that does not exist: an error naming the file, nothing written.
    expect_clean_error(run_stex({"render", texture, "-o", (dir / "missing" / "o.exr").string()}, dir), "o.exr");
    expect_clean_error(run_stex({"analyze", photo, "-o", (dir / "missing" / "t.stex").string(), "--model", "wavelet"}, dir), "t.stex");
}

// The ptm writers (coefficient maps, normal maps, light lists) go through the same safe write:
// past a file-size limit each fails with its file named, the previous output stays as it was
// and no temporary is left. Before, the normal map and the light list were truncated in place.
TEST(HardeningPtm, FailedWritesKeepThePreviousOutputs)
{
    const fs::path dir = stochtex::test::temp_dir("FailedPtmWrite");
    std::mt19937 random(16);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    auto noise = [&](int side, int channels) {  // incompressible, so that the files are large
        stochtex::Image image(side, side, channels);
        for (float& v : image.pixels) v = unit(random);
        return image;
    };
    auto coefficients = [&](int side) {
        stochtex::PtmMaps maps;
        maps.coefficients = noise(side, stochtex::ptm_channel_count(maps.colour));
        return maps;
    };
    auto lights = [](int count) {
        stochtex::LightSet set;
        for (int i = 0; i < count; ++i) {
            set.images.push_back("photo-" + std::to_string(i) + ".png");
            set.directions.push_back({0.0, 0.0, 1.0});
        }
        return set;
    };
    struct Writer {
        std::string name;
        std::function<void(const std::string&, bool large)> write;
    };
    const Writer writers[] = {
        {"c.exr", [&](const std::string& path, bool large) { write_ptm_coefficients(path, coefficients(large ? 256 : 8)); }},
        {"n.exr", [&](const std::string& path, bool large) { write_normal_map(path, noise(large ? 256 : 8, 3)); }},
        {"n.png", [&](const std::string& path, bool large) { write_normal_map(path, noise(large ? 256 : 8, 3)); }},
        {"l.lp", [&](const std::string& path, bool large) { write_light_set(path, lights(large ? 4000 : 2)); }},
    };
    for (const Writer& writer : writers) {
        const std::string out = (dir / writer.name).string();
        writer.write(out, false);
        const std::string before = read_bytes(out);
        ASSERT_FALSE(before.empty()) << writer.name;
        const std::vector<std::string> files = files_in(dir);
        rlimit old_limit{};
        getrlimit(RLIMIT_FSIZE, &old_limit);
        rlimit limit = old_limit;
        limit.rlim_cur = 32 * 1024;  // each large output is well above it, each small one below
        signal(SIGXFSZ, SIG_IGN);
        setrlimit(RLIMIT_FSIZE, &limit);
        const std::string message = error_of([&] { writer.write(out, true); });
        setrlimit(RLIMIT_FSIZE, &old_limit);
        EXPECT_TRUE(contains(message, out)) << writer.name << ": " << message;
        EXPECT_TRUE(read_bytes(out) == before) << writer.name << " was changed";
        EXPECT_EQ(files_in(dir), files) << writer.name << ": a temporary was left behind";
    }
    // A folder that does not exist: an error naming the file, nothing written.
    const std::string missing = (dir / "missing" / "m.lp").string();
    EXPECT_TRUE(contains(error_of([&] { write_light_set(missing, lights(2)); }), missing));
    EXPECT_TRUE(contains(error_of([&] { write_ptm_coefficients((dir / "missing" / "m.exr").string(), coefficients(8)); }),
                         "m.exr"));
}

// SIGINT in the middle of a bake: the previous map is byte-identical and no temporary remains.
TEST(HardeningCli, InterruptedBakeKeepsThePreviousOutput)
{
    const fs::path dir = stochtex::test::temp_dir("InterruptedBake");
    const std::string texture = (dir / "w.stex").string(), out = (dir / "map.exr").string();
    ASSERT_TRUE(run_stex({"analyze", stochtex::test::repo_exemplar("concrete_512.png"), "-o", texture, "--model", "wavelet"}, dir).succeeded());
    ASSERT_TRUE(run_stex({"bake", texture, "-o", out, "--size", "64"}, dir).succeeded());
    const std::string before = read_bytes(out);
    const std::vector<std::string> files = files_in(dir);

    const auto program = stochtex::test::start_program({STOCHTEX_CLI, "bake", texture, "-o", out, "--size", "8192"}, dir.string());
    ASSERT_EQ(program.spawn_error, 0);
    // Interrupt once the temporary exists (the bake is writing), at least a second in.
    const auto start = std::chrono::steady_clock::now();
    bool writing = false;
    while (!writing && std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        for (const std::string& name : files_in(dir)) writing = writing || contains(name, ".tmp");
    }
    std::this_thread::sleep_until(start + std::chrono::seconds(1));
    kill(program.pid, SIGINT);
    const auto r = stochtex::test::finish_program(program);
    EXPECT_TRUE(writing) << "the bake never started writing\n" << r;
    EXPECT_FALSE(r.exited) << "the bake finished before the interrupt\n" << r;
    EXPECT_EQ(r.signal, SIGINT) << r;
    EXPECT_TRUE(read_bytes(out) == before) << "the previous map was changed";
    EXPECT_EQ(files_in(dir), files) << "a temporary was left behind";
}

// ---- Reading images for analysis ----------------------------------------------------------------

/// A PNG of only a header (IHDR, an empty IDAT, IEND) claiming width × height RGB pixels.
void write_png_header(const fs::path& path, std::uint32_t width, std::uint32_t height)
{
    auto crc32 = [](const std::string& bytes) {
        std::uint32_t crc = 0xffffffffu;
        for (unsigned char b : bytes) {
            crc ^= b;
            for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
        }
        return ~crc;
    };
    auto be32 = [](std::uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    };
    auto chunk = [&](const std::string& type, const std::string& data) {
        return be32(std::uint32_t(data.size())) + type + data + be32(crc32(type + data));
    };
    const std::string ihdr = be32(width) + be32(height) + std::string{8, 2, 0, 0, 0};
    const std::string empty_zlib{'\x78', '\x9c', '\x03', '\x00', '\x00', '\x00', '\x00', '\x01'};
    std::ofstream(path, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << chunk("IHDR", ihdr)
                                          << chunk("IDAT", empty_zlib) << chunk("IEND", "");
}

TEST(Hardening, ImageReadingChecksTheHeaderBeforeThePixels)
{
    const fs::path dir = stochtex::test::temp_dir("ImageLimits");
    // Was 3.1 GB of memory before failing: 74 bytes claiming 16000².
    write_png_header(dir / "huge.png", 16000, 16000);
    std::string message = error_of([&] { stochtex::read_image_linear((dir / "huge.png").string()); });
    EXPECT_TRUE(contains(message, "huge.png") && contains(message, "too large") && contains(message, "2^26")) << message;
    write_png_header(dir / "wide.png", 20000, 16);
    message = error_of([&] { stochtex::read_image_linear((dir / "wide.png").string()); });
    EXPECT_TRUE(contains(message, "wide.png") && contains(message, "16384")) << message;

    message = error_of([&] { stochtex::read_image_linear(dir.string()); });
    EXPECT_TRUE(contains(message, "is a directory")) << message;
}

// A JPEG cut to 25 % of its length decoded its missing rows as flat grey with only a warning.
TEST(Hardening, TruncatedJpegIsRejected)
{
    const fs::path dir = stochtex::test::temp_dir("TruncatedJpeg");
    const fs::path full = dir / "full.jpg", cut = dir / "cut.jpg";
    {
        const stochtex::Image& image = exemplar();
        auto output = OIIO::ImageOutput::create(full.string());
        ASSERT_TRUE(output);
        OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
        ASSERT_TRUE(output->open(full.string(), spec));
        ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
        ASSERT_TRUE(output->close());
    }
    ASSERT_NO_THROW(stochtex::read_image_linear(full.string()));
    const std::string bytes = read_bytes(full);
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 4);
    const std::string message = error_of([&] { stochtex::read_image_linear(cut.string()); });
    EXPECT_TRUE(contains(message, "cut.jpg") && contains(message, "truncated")) << message;
}

}  // namespace

// ---- Light sidecars (issue 16's .lp findings) -------------------------------------------------

namespace {

/// `count` photos of the exemplar's top-left 16² (colour, or grey with 1 channel) in `dir`.
void write_photos(const fs::path& dir, const std::vector<std::string>& names, int grey_from = 1 << 30)
{
    const stochtex::Image colour = crop(16);
    for (std::size_t i = 0; i < names.size(); ++i) {
        const std::string path = (dir / names[i]).string();
        if (int(i) < grey_from) {
            stochtex::write_image(path, colour);
            continue;
        }
        // A 1-channel PNG, as a grey export writes it.
        std::vector<unsigned char> grey(16 * 16);
        for (std::size_t p = 0; p < grey.size(); ++p) grey[p] = (unsigned char)(40 + p % 200);
        auto output = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(output && output->open(path, OIIO::ImageSpec(16, 16, 1, OIIO::TypeDesc::UINT8)) &&
                    output->write_image(OIIO::TypeDesc::UINT8, grey.data()) && output->close());
    }
}

std::string lp_text(const std::vector<std::string>& names)
{
    const std::vector<stochtex::Vec3> directions = stochtex::spiral_light_directions(int(names.size()), 20);
    std::string text = std::to_string(names.size()) + "\n";
    for (std::size_t i = 0; i < names.size(); ++i) {
        char direction[96];
        std::snprintf(direction, sizeof direction, " %.9g %.9g %.9g\n", directions[i][0], directions[i][1], directions[i][2]);
        text += names[i] + direction;
    }
    return text;
}

void write_text(const fs::path& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary);
    out << text;
}

}  // namespace

// Was: the same photo under two spellings (or through a link) was fitted twice, silently
// weighting its light double. Now an error naming both lines (.lp) or entries (JSON).
TEST(HardeningPtm, OnePhotoUnderTwoNamesIsRejectedNamingBoth)
{
    const fs::path dir = stochtex::test::temp_dir("LightSetSameFile");
    fs::create_directories(dir / "sub");
    write_photos(dir, {"a.png", "b.png"});
    fs::create_symlink(dir / "a.png", dir / "link.png");
    fs::create_hard_link(dir / "b.png", dir / "hard.png");
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"a.png", "b.png", "./a.png"}, "lights.lp:4: image './a.png' is the same file as 'a.png' on line 2"},
        {{"a.png", "sub/../b.png", "b.png"}, "lights.lp:4: image 'b.png' is the same file as 'sub/../b.png' on line 3"},
        {{"a.png", "b.png", "link.png"}, "lights.lp:4: image 'link.png' is the same file as 'a.png' on line 2"},
        {{"hard.png", "a.png", "b.png"}, "lights.lp:4: image 'b.png' is the same file as 'hard.png' on line 2"},
        {{"a.png", "b.png", (dir / "a.png").string()}, "is the same file as 'a.png' on line 2"},
    };
    for (const auto& [names, message] : cases) {
        write_text(dir / "lights.lp", lp_text(names));
        const std::string error = error_of([&] { stochtex::read_light_set((dir / "lights.lp").string()); });
        EXPECT_TRUE(contains(error, message)) << error;
    }
    write_text(dir / "lights.json", R"({"lights": [{"image": "a.png", "direction": [0, 0, 1]},
                                                    {"image": "./link.png", "direction": [0.6, 0, 0.8]}]})");
    const std::string error = error_of([&] { stochtex::read_light_set((dir / "lights.json").string()); });
    EXPECT_TRUE(contains(error, "lights[1].image: './link.png' is the same file as 'a.png' at lights[0]")) << error;
    // Distinct files (and names of files not there yet, for the reader alone) are fine.
    write_text(dir / "lights.lp", lp_text({"a.png", "b.png", "sub/a.png"}));
    EXPECT_EQ(stochtex::read_light_set((dir / "lights.lp").string()).images.size(), 3u);
}

// Was: a 1-channel photo among RGB ones was read as grey RGB and fitted, giving its light a
// wrong chroma. Decided: rejected, naming both photos (an all-grey set is consistent and fits).
TEST(HardeningPtm, GreyPhotoAmongColourPhotosIsRejected)
{
    const fs::path dir = stochtex::test::temp_dir("LightSetGrey");
    const std::vector<std::string> names{"p0.png", "p1.png", "p2.png", "p3.png", "p4.png", "p5.png", "p6.png"};
    write_photos(dir, names, 6);  // the last one grey
    write_text(dir / "lights.lp", lp_text(names));
    const stochtex::LightSet set = stochtex::read_light_set((dir / "lights.lp").string());
    const std::string error = error_of([&] { stochtex::read_light_set_photos(set); });
    EXPECT_TRUE(contains(error, "p6.png: the photo is grey (1 channel) but ")) << error;
    EXPECT_TRUE(contains(error, "p0.png is colour (3 channels)")) << error;
    const auto r = run_stex({"ptm", "fit", (dir / "lights.lp").string(), "-o", (dir / "t.stex").string()}, dir);
    expect_clean_error(r, "p6.png");
    EXPECT_FALSE(fs::exists(dir / "t.stex"));

    const fs::path all_grey = stochtex::test::temp_dir("LightSetAllGrey");
    write_photos(all_grey, names, 0);
    write_text(all_grey / "lights.lp", lp_text(names));
    const std::vector<stochtex::Image> photos =
        stochtex::read_light_set_photos(stochtex::read_light_set((all_grey / "lights.lp").string()));
    ASSERT_EQ(photos.size(), names.size());
    EXPECT_EQ(photos[0].channels, 3);
    EXPECT_EQ(photos[0].at(3, 2, 0), photos[0].at(3, 2, 2));  // grey replicated
}

// Was: "fit residual RMSE 0.00000 (-nan %)" for photos that are all black.
TEST(HardeningPtm, BlackPhotosFitWithoutANanPercentage)
{
    const fs::path dir = stochtex::test::temp_dir("LightSetBlack");
    const std::vector<std::string> names{"b0.png", "b1.png", "b2.png", "b3.png", "b4.png", "b5.png", "b6.png", "b7.png"};
    for (const std::string& name : names) stochtex::write_image((dir / name).string(), stochtex::Image(16, 16, 3));
    write_text(dir / "lights.lp", lp_text(names));
    const auto r = run_stex({"ptm", "fit", (dir / "lights.lp").string(), "-o", (dir / "t.stex").string()}, dir);
    ASSERT_TRUE(r.succeeded()) << r;
    EXPECT_FALSE(contains(r.out, "nan")) << r;
    EXPECT_TRUE(contains(r.out, "fit residual RMSE 0.00000 (no relative error: the photos are black, RMS 0)")) << r;
}

// ---- Outputs checked before the work ----------------------------------------------------------

// Was: a render's output format and folder were found wrong only after the whole render. Each
// writer checks its output first (check_image_output / check_output_path): a 16384² render, a
// 32768² bake or an analysis with a bad output fails at once, naming the file and the problem.
TEST(HardeningCli, OutputFormatAndFolderAreCheckedBeforeTheWork)
{
    const fs::path dir = stochtex::test::temp_dir("OutputChecks");
    const std::string texture = (dir / "w.stex").string();
    stochtex::write_stex(texture, analysed("wavelet"));
    fs::create_directories(dir / "folder.exr");
    fs::create_directories(dir / "locked");
    fs::permissions(dir / "locked", fs::perms::owner_read | fs::perms::owner_exec);
    const std::string photo = stochtex::test::repo_exemplar("concrete_512.png");
    const std::string missing = (dir / "missing").string();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"render", texture, "--size", "16384x16384", "-o", (dir / "o.xyz").string()},
         "o.xyz: cannot write image: '.xyz' is not an image format OpenImageIO writes"},
        {{"render", texture, "--size", "16384x16384", "-o", (dir / "noextension").string()},
         "noextension: cannot write image: no extension to choose a format by"},
        {{"render", texture, "--size", "16384x16384", "-o", missing + "/o.exr"},
         "o.exr: cannot write image: the folder " + missing + " does not exist"},
        {{"render", texture, "--size", "16384x16384", "-o", (dir / "folder.exr").string()}, "folder.exr: cannot write image: it is a folder"},
        {{"bake", texture, "--size", "32768", "-o", (dir / "b.png").string()}, "b.png: the png format cannot hold a tiled"},
        {{"bake", texture, "--size", "32768", "-o", missing + "/b.exr"}, "b.exr: cannot write the bake: the folder"},
        {{"analyze", photo, "--model", "lrp", "-o", missing + "/t.stex"}, "t.stex: cannot write the texture: the folder"},
        {{"pov", texture, "--mode", "baked", "-o", missing + "/t.inc"}, "t.inc: cannot write the include: the folder"},
        {{"compare", photo, texture, "-o", (dir / "figure.xyz").string()}, "figure.xyz: cannot write the figure"},
    };
    for (const auto& [args, message] : cases) {
        const auto start = std::chrono::steady_clock::now();
        const auto r = run_stex(args, dir);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        expect_clean_error(r, message);
        EXPECT_LT(seconds, 20) << "the check came after the work: " << r;  // the work alone takes minutes
    }
    if (geteuid() != 0) {  // root writes anywhere
        const auto r = run_stex({"render", texture, "-o", (dir / "locked" / "o.exr").string()}, dir);
        expect_clean_error(r, "is not writable");
    }
    // The library's own checks, for other callers.
    EXPECT_EQ(error_of([&] { stochtex::check_image_output((dir / "a.exr").string()); }), "");
    EXPECT_TRUE(contains(error_of([&] { stochtex::check_image_output((dir / "a.doc").string()); }), "'.doc' is not an image format"));
}
