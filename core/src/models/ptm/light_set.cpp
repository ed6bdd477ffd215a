// Light sidecars: which photo was taken under which light (docs/models/ptm.md, "Input").
#include <stochtex/atomic_write.h>
#include <stochtex/error.h>
#include <stochtex/models/ptm.h>

#include "schema/json_fields.h"
#include "numerics/constants.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include <sys/stat.h>

namespace stochtex {

namespace fs = std::filesystem;

namespace {

constexpr double unit_length_tolerance = 0.01;
constexpr int max_lights = 4096;

std::string read_text(const std::string& path)
{
    std::error_code ignored;
    if (fs::is_directory(path, ignored)) throw Error(path + ": cannot read: is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open the light sidecar");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string resolve(const std::string& image, const std::string& sidecar)
{
    const fs::path path(image);
    return path.is_absolute() ? image : (fs::path(sidecar).parent_path() / path).lexically_normal().string();
}

std::vector<std::string> tokens_of(const std::string& line)
{
    std::istringstream in(line);
    return {std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
}

/// What identifies a photo's file however it is spelled ("a.png", "./a.png", "sub/../a.png", a
/// symbolic or hard link): its device and inode where it exists, else its canonical path.
std::string file_identity(const std::string& resolved)
{
    struct stat status {};
    if (stat(resolved.c_str(), &status) == 0)
        return "inode " + std::to_string(status.st_dev) + ":" + std::to_string(status.st_ino);
    std::error_code ignored;
    const fs::path canonical = fs::weakly_canonical(resolved, ignored);
    return canonical.empty() ? resolved : canonical.string();
}

bool parse_number(const std::string& text, double& value)
{
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    return error == std::errc() && stop == end;
}

/// The common RTI list: the light count on the first line, then "image x y z" per line (the
/// image name may contain spaces: the last three fields are the direction).
LightSet read_lp(const std::string& path, const std::string& text)
{
    std::istringstream in(text);
    std::string line;
    int line_number = 0;
    auto fail = [&](const std::string& problem) -> void {
        throw Error(path + ":" + std::to_string(line_number) + ": " + problem);
    };
    long long expected = -1;
    LightSet lights;
    std::map<std::string, std::pair<int, std::string>> first_line_of;  // file identity → line, name
    while (std::getline(in, line)) {
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::vector<std::string> fields = tokens_of(line);
        if (fields.empty()) continue;  // blank lines carry nothing
        if (expected < 0) {
            double count = 0;
            if (fields.size() != 1 || !parse_number(fields[0], count) || count != std::floor(count) || count < 1 ||
                count > max_lights)
                fail("expected the number of lights (an integer 1 … " + std::to_string(max_lights) + "), got '" + line +
                     "'");
            expected = static_cast<long long>(count);
            continue;
        }
        if (fields.size() < 4) fail("expected 'image x y z', got '" + line + "'");
        Vec3 direction{};
        for (int k = 0; k < 3; ++k)
            if (!parse_number(fields[fields.size() - 3 + k], direction[k]))
                fail(std::string("direction component ") + "xyz"[k] + " is not a number: '" +
                     fields[fields.size() - 3 + k] + "'");
        // The name is the line up to the direction, so names with spaces survive.
        std::size_t end = line.find_last_not_of(" \t");
        for (int k = 0; k < 3; ++k) {
            end = line.find_last_of(" \t", end);             // before the k-th field from the end
            end = line.find_last_not_of(" \t", end);          // the end of the field before it
        }
        std::string name = line.substr(0, end + 1);
        name.erase(0, name.find_first_not_of(" \t"));
        if (lights.images.size() == std::size_t(expected))
            fail("more lights than the " + std::to_string(expected) + " announced on the first line");
        try {
            direction = checked_light_direction(direction, "direction");
        } catch (const Error& e) {
            fail(e.what());
        }
        const std::string resolved = resolve(name, path);
        const auto [previous, inserted] = first_line_of.emplace(file_identity(resolved), std::make_pair(line_number, name));
        if (!inserted)
            fail("image '" + name + "' is " +
                 (name == previous->second.second
                      ? "listed twice (first on line " + std::to_string(previous->second.first) + ")"
                      : "the same file as '" + previous->second.second + "' on line " + std::to_string(previous->second.first)) +
                 " (each photo once: a photo listed twice is fitted twice)");
        lights.images.push_back(resolved);
        lights.directions.push_back(direction);
    }
    if (expected < 0) throw Error(path + ": empty light list (expected the number of lights on the first line)");
    if (lights.images.size() != std::size_t(expected))
        throw Error(path + ": the first line announces " + std::to_string(expected) + " lights, the file lists " +
                    std::to_string(lights.images.size()));
    return lights;
}

LightSet read_json(const std::string& path, const std::string& text)
{
    using json_fields::Field;
    const json_fields::Json json = json_fields::parse(text, path);
    const Field root(json, path);
    root.expect_keys({"lights"});
    const std::vector<Field> entries = root["lights"].elements();
    if (entries.empty() || entries.size() > std::size_t(max_lights))
        root["lights"].fail("expected 1 … " + std::to_string(max_lights) + " lights, got " + std::to_string(entries.size()));
    LightSet lights;
    std::map<std::string, std::pair<std::size_t, std::string>> first_index_of;  // file identity → index, name
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Field& entry = entries[i];
        entry.expect_keys({"image", "direction"});
        const std::string image = entry["image"].string();
        if (image.empty()) entry["image"].fail("must not be empty");
        const std::string resolved = resolve(image, path);
        const auto [previous, inserted] = first_index_of.emplace(file_identity(resolved), std::make_pair(i, image));
        if (!inserted)
            entry["image"].fail("'" + image + "' is " +
                                (image == previous->second.second
                                     ? "listed twice (first at lights[" + std::to_string(previous->second.first) + "])"
                                     : "the same file as '" + previous->second.second + "' at lights[" +
                                           std::to_string(previous->second.first) + "]") +
                                " (each photo once: a photo listed twice is fitted twice)");
        const Field direction = entry["direction"];
        try {
            lights.directions.push_back(checked_light_direction(direction.numbers<3>(), "direction"));
        } catch (const Error& e) {
            // Type errors already name the field; range errors get its path here.
            const std::string message = e.what();
            if (message.rfind(path, 0) == 0) throw;
            direction.fail(message.substr(message.find(": ") + 2));
        }
        lights.images.push_back(resolved);
    }
    return lights;
}

}  // namespace

Vec3 checked_light_direction(const Vec3& direction, const std::string& what)
{
    const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    auto shown = [&] {
        std::ostringstream text;
        text << "(" << direction[0] << ", " << direction[1] << ", " << direction[2] << ")";
        return text.str();
    };
    if (!std::isfinite(length)) throw Error(what + ": " + shown() + " is not a finite vector");
    if (!(std::fabs(length - 1) <= unit_length_tolerance))
        throw Error(what + ": " + shown() + " is not a unit vector (length " + std::to_string(length) + ")");
    if (!(direction[2] > 0))
        throw Error(what + ": " + shown() + " points below the surface (z must be positive)");
    return {direction[0] / length, direction[1] / length, direction[2] / length};
}

namespace {

std::string sidecar_extension(const std::string& path)
{
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".lp" && extension != ".json")
        throw Error(path + ": unknown light sidecar type '" + extension + "' (expected .lp or .json)");
    return extension;
}

}  // namespace

LightSet parse_light_set(const std::string& text, const std::string& path)
{
    return sidecar_extension(path) == ".lp" ? read_lp(path, text) : read_json(path, text);
}

LightSet read_light_set(const std::string& path)
{
    sidecar_extension(path);  // an unknown type is reported before the file is read
    return parse_light_set(read_text(path), path);
}

std::vector<Image> read_light_set_photos(const LightSet& lights, const ImageReadOptions& options, int min_size)
{
    std::vector<Image> photos;
    std::vector<ImageFileInfo> infos(lights.images.size());
    for (std::size_t i = 0; i < lights.images.size(); ++i) {
        photos.push_back(read_image_linear(lights.images[i], options, min_size, &infos[i]));
        const Image& first = photos.front();
        const std::string& first_name = lights.images.front();
        const auto kind = [](const ImageFileInfo& info) {
            return info.colour_channels == 1 ? std::string("grey (1 channel)") : std::string("colour (3 channels)");
        };
        if (infos[i].colour_channels != infos[0].colour_channels)
            throw Error(lights.images[i] + ": the photo is " + kind(infos[i]) + " but " + first_name + " is " +
                        kind(infos[0]) + ": the photos of one light set must be all colour or all grey");
        if (photos[i].width != first.width || photos[i].height != first.height)
            throw Error(lights.images[i] + ": the photo is " + std::to_string(photos[i].width) + "x" +
                        std::to_string(photos[i].height) + " but " + first_name + " is " + std::to_string(first.width) +
                        "x" + std::to_string(first.height) + " (one camera, one size)");
    }
    return photos;
}

void write_light_set(const std::string& path, const LightSet& lights)
{
    if (lights.images.size() != lights.directions.size())
        throw Error(path + ": " + std::to_string(lights.images.size()) + " images but " +
                    std::to_string(lights.directions.size()) + " directions");
    std::ostringstream text;
    text << lights.images.size() << "\n";
    const fs::path folder = fs::absolute(path).parent_path();
    for (std::size_t i = 0; i < lights.images.size(); ++i) {
        const fs::path relative = fs::absolute(lights.images[i]).lexically_relative(folder);
        const std::string name = relative.empty() ? lights.images[i] : relative.string();
        char direction[96];
        std::snprintf(direction, sizeof direction, " %.9g %.9g %.9g", lights.directions[i][0], lights.directions[i][1],
                      lights.directions[i][2]);
        text << name << direction << "\n";
    }
    write_file_atomically(path, text.str());
}

std::vector<Vec3> spiral_light_directions(int count, double min_elevation_degrees, double azimuth_offset_degrees)
{
    if (count < 1) throw Error("light directions: the count must be positive");
    if (!(min_elevation_degrees >= 0 && min_elevation_degrees < 90))
        throw Error("light directions: the minimum elevation must be in [0, 90) degrees");
    // z uniform on [sin(min elevation), 1] is uniform in solid angle; the golden angle between
    // consecutive azimuths spreads every prefix of the sequence evenly too.
    const double z_min = std::sin(min_elevation_degrees * kPi / 180);
    const double golden_angle = kPi * (3 - std::sqrt(5.0));
    std::vector<Vec3> directions;
    for (int k = 0; k < count; ++k) {
        const double z = z_min + (1 - z_min) * (k + 0.5) / count;
        const double phi = k * golden_angle + azimuth_offset_degrees * kPi / 180;
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        directions.push_back({r * std::cos(phi), r * std::sin(phi), z});
    }
    return directions;
}

}  // namespace stochtex
