// libFuzzer harness: the coefficient EXR a ptm .stex refers to (read_ptm_coefficients: its size
// limits, channel names and count). The first byte chooses the colour form (lrgb or rgb).
#include "fuzz_support.h"

#include "models/ptm/ptm_coefficient_file.h"

#include <stochtex/error.h>

#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace stochtex;
    if (size == 0) return 0;
    const PtmColour colour = data[0] % 2 ? PtmColour::rgb : PtmColour::lrgb;
    const std::string path = fuzz::scratch_file("coefficients.ptm.exr", data + 1, size - 1);
    try {
        const PtmMaps maps = read_ptm_coefficients(path, colour, "fuzz.stex: parameters.coefficients.file");
        if (maps.width() < 1 || maps.width() > max_ptm_side || maps.height() < 1 || maps.height() > max_ptm_side ||
            maps.coefficients.channels != ptm_channel_count(colour))
            std::abort();
    } catch (const Error&) {
    }
    return 0;
}
