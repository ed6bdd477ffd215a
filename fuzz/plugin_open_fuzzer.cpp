// libFuzzer harness: the OIIO plugin's open() with open-time configuration hints, then a tile of
// the finest and of the coarsest MIP level. The input is hint lines "name=value" (a value that is
// an integer becomes an int attribute, a number a float, anything else a string: as oiiotool's
// --iconfig passes them), a line "---", then the .stex text.
#include "fuzz_support.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

// The plugin's factory (plugin/stex_input.cpp is compiled into this program).
extern "C" OIIO::ImageInput* stex_input_imageio_create();

namespace {

void add_hint(OIIO::ImageSpec& config, const std::string& line)
{
    const std::size_t equals = line.find('=');
    if (equals == std::string::npos || equals == 0) return;
    const std::string name = line.substr(0, equals), value = line.substr(equals + 1);
    const char* end = value.data() + value.size();
    long long integer = 0;
    double number = 0;
    if (auto [stop, error] = std::from_chars(value.data(), end, integer); error == std::errc() && stop == end &&
                                                                          !value.empty() && integer == int(integer))
        config.attribute(name, int(integer));
    else if (auto [stop2, error2] = std::from_chars(value.data(), end, number); error2 == std::errc() && stop2 == end)
        config.attribute(name, float(number));
    else
        config.attribute(name, value);
}

bool read_tile(OIIO::ImageInput& input, int level)
{
    if (!input.seek_subimage(0, level)) return false;
    const OIIO::ImageSpec spec = input.spec(0, level);
    if (spec.tile_width <= 0 || spec.tile_height <= 0) std::abort();  // the plugin is always tiled
    std::vector<float> tile(std::size_t(spec.tile_width) * spec.tile_height * spec.nchannels);
    if (!input.read_native_tile(0, level, 0, 0, 0, tile.data())) return false;
    for (float v : tile)
        if (!std::isfinite(v)) std::abort();
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::size_t separator = input.find("---\n");
    if (separator == std::string::npos) return 0;
    OIIO::ImageSpec config;
    std::size_t start = 0;
    while (start < separator) {
        const std::size_t end = std::min(input.find('\n', start), separator);
        add_hint(config, input.substr(start, end - start));
        start = end + 1;
    }
    // In the scratch folder, which links the seed corpus's ptm coefficient files: a seed's
    // coefficient file reference resolves as it did beside the .stex it came from.
    const std::string text = input.substr(separator + 4);
    const std::string file =
        stochtex::fuzz::scratch_file("plugin.stex", reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
    std::unique_ptr<OIIO::ImageInput> plugin(stex_input_imageio_create());
    OIIO::ImageSpec spec;
    if (!plugin->open(file, spec, config)) {
        (void)plugin->geterror();
        return 0;
    }
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1 || spec.nchannels > 4) std::abort();
    int levels = 0;
    while (plugin->seek_subimage(0, levels)) ++levels;
    if (levels < 1) std::abort();
    // The coarsest level always; the finest when its tile is small (a 4096² tile is valid but
    // costs 256 MiB: the limits allow it, the fuzzer's memory budget does not need it).
    if (!read_tile(*plugin, levels - 1)) std::abort();
    if (spec.tile_width * spec.tile_height <= 256 * 256 && !read_tile(*plugin, 0)) std::abort();
    plugin->close();
    return 0;
}
