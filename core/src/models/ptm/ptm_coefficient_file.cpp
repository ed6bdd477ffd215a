#include "models/ptm/ptm_coefficient_file.h"

#include "image/image_output.h"

#include <stochtex/error.h>
#include <stochtex/models/ptm_parameters.h>


#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace stochtex {

namespace fs = std::filesystem;

std::string ptm_checksum(const PtmMaps& maps)
{
    std::uint64_t hash = 0xcbf29ce484222325ull;
    auto feed = [&](std::uint32_t word) {
        for (int byte = 0; byte < 4; ++byte) {
            hash ^= (word >> (8 * byte)) & 0xffu;  // little-endian order on every machine
            hash *= 0x100000001b3ull;
        }
    };
    feed(std::uint32_t(maps.width()));
    feed(std::uint32_t(maps.height()));
    feed(std::uint32_t(maps.coefficients.channels));
    for (float value : maps.coefficients.pixels) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &value, sizeof bits);
        feed(bits);
    }
    char text[32];
    std::snprintf(text, sizeof text, "fnv1a64:%016llx", static_cast<unsigned long long>(hash));
    return text;
}

PtmMaps read_ptm_coefficients(const std::string& path, PtmColour colour, const std::string& what)
{
    auto fail = [&](const std::string& problem) -> void { throw Error(what + ": " + problem); };
    if (!fs::is_regular_file(path)) fail("coefficient file '" + path + "' does not exist");
    std::string error;
    const auto input = codec::open_image(path, error, /*by_name=*/true);
    if (!input) fail("cannot read coefficient file '" + path + "': " + error);
    const codec::ImageHeader spec = input->header();
    if (spec.width < 1 || spec.height < 1 || spec.width > max_ptm_side || spec.height > max_ptm_side ||
        (long long)spec.width * spec.height > max_ptm_texels)
        fail("coefficient maps of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
             " texels exceed the limits (sides 1 … 4096, at most 2^22 texels)");
    // OpenEXR sorts channels by name: map each expected channel to its place in the file.
    const std::vector<std::string> names = ptm_channel_names(colour);
    if (spec.channels != int(names.size()))
        fail("coefficient file '" + path + "' has " + std::to_string(spec.channels) + " channels, a " +
             to_string(colour) + " PTM has " + std::to_string(names.size()));
    std::vector<int> file_channel;
    for (const std::string& name : names) {
        const auto found = std::find(spec.channel_names.begin(), spec.channel_names.end(), name);
        if (found == spec.channel_names.end()) fail("coefficient file '" + path + "' has no channel '" + name + "'");
        file_channel.push_back(int(found - spec.channel_names.begin()));
    }
    std::vector<float> data(std::size_t(spec.width) * spec.height * spec.channels);
    error = input->read(spec.channels, data.data());
    if (!error.empty()) fail("cannot read the pixels of '" + path + "': " + error);
    PtmMaps maps;
    maps.colour = colour;
    maps.coefficients = Image(spec.width, spec.height, spec.channels);
    for (std::size_t i = 0; i < maps.coefficients.pixel_count(); ++i)
        for (std::size_t k = 0; k < names.size(); ++k) {
            const float value = data[i * spec.channels + file_channel[k]];
            if (!std::isfinite(value))
                fail("coefficient file '" + path + "': texel (" + std::to_string(i % spec.width) + ", " +
                     std::to_string(i / spec.width) + ") channel " + names[k] + " is not finite");
            maps.coefficients.pixels[i * names.size() + k] = value;
        }
    return maps;
}

void write_ptm_coefficients(const std::string& path, const PtmMaps& maps)
{
    const std::vector<std::string> names = ptm_channel_names(maps.colour);
    if (maps.coefficients.channels != int(names.size()) || maps.width() < 1)
        throw Error(path + ": cannot write empty maps or maps with a wrong channel count");
    codec::ImageHeader spec;
    spec.width = maps.width(), spec.height = maps.height(), spec.channels = int(names.size());
    spec.channel_names = names;
    spec.set("compression", "zip");
    spec.set("Software", "stochtex " STOCHTEX_VERSION);
    spec.set("ImageDescription", std::string("stochtex PTM coefficient maps (") + to_string(maps.colour) +
                                     ", Legendre basis; docs/stex-format.md)");
    // A failed write keeps the maps that a .stex beside them already names.
    write_image_file(path, spec, maps.coefficients.pixels.data(), "the coefficient maps");
}

}  // namespace stochtex
