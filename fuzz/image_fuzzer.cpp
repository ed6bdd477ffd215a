// libFuzzer harness: image loading for analysis, read_image_linear() with its limits (sizes from
// the header, truncation, non-finite values). The first byte chooses the file's extension (PNG,
// JPEG, EXR), which picks OIIO's first reader; OIIO falls back to the others by content.
#include "fuzz_support.h"

#include <stochtex/error.h>
#include <stochtex/image.h>

#include <cmath>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0) return 0;
    static const char* extensions[] = {"png", "jpg", "exr"};
    const std::string path = stochtex::fuzz::scratch_file(std::string("image.") + extensions[data[0] % 3], data + 1, size - 1);
    try {
        const stochtex::Image image = stochtex::read_image_linear(path);
        if (image.channels != 3 || image.width < 16 || image.height < 16 || image.width > stochtex::max_read_side ||
            image.height > stochtex::max_read_side)
            std::abort();
        for (float v : image.pixels)
            if (!std::isfinite(v)) std::abort();
    } catch (const stochtex::Error&) {
    }
    return 0;
}
