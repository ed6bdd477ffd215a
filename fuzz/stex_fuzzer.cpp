// libFuzzer harness: the .stex reader, every model's parameter block with it (the embedded
// exemplar PNG and its base64 for tiling, the coefficient file reference for ptm), then what a
// file it accepts must also do: write canonically (format → parse → format is byte-identical)
// and make a texture whose small filtered render is finite.
#include "fuzz_support.h"

#include <stochtex/error.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <cmath>
#include <cstdlib>
#include <string>

constexpr std::size_t max_size_to_render = 8192;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace stochtex;
    static const std::string source = fuzz::data_dir() + "/fuzz.stex";
    TextureDescription description;
    try {
        description = parse_stex(std::string(reinterpret_cast<const char*>(data), size), source);
    } catch (const Error&) {
        return 0;  // a clean rejection; anything else thrown is a finding (libFuzzer reports it)
    }
    const std::string canonical = format_stex(description);
    if (format_stex(parse_stex(canonical, source)) != canonical) std::abort();
    // Textures are made from small files only: a file with an embedded exemplar (tiling) costs
    // seconds to prepare under ASan at -O1, which would leave the parser a few executions a
    // second. Its parsing, base64 and PNG decoding are fuzzed all the same.
    if (size > max_size_to_render) return 0;
    try {
        RenderSettings settings;
        settings.width = settings.height = 4;
        settings.units_per_pixel = 1.7 / description.pixels_per_unit;
        settings.origin_u = -0.3;
        settings.threads = 1;
        const Image image = render(*make_texture(description), settings);
        for (float v : image.pixels)
            if (!std::isfinite(v)) std::abort();  // an accepted file must not render NaN
    } catch (const Error&) {
    }
    return 0;
}
