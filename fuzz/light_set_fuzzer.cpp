// libFuzzer harness: the ptm light sidecars. The first byte chooses the format (even: .lp, the
// RTI list; odd: the JSON list), the rest is the file's text.
#include <stochtex/error.h>
#include <stochtex/models/ptm.h>

#include <cmath>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0) return 0;
    const std::string path = data[0] % 2 ? "/fuzz/lights.json" : "/fuzz/lights.lp";
    try {
        const stochtex::LightSet lights =
            stochtex::parse_light_set(std::string(reinterpret_cast<const char*>(data + 1), size - 1), path);
        // What the reader promises: one unit direction above the surface per image.
        if (lights.images.empty() || lights.images.size() != lights.directions.size()) std::abort();
        for (const stochtex::Vec3& d : lights.directions)
            if (!(std::fabs(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1) < 1e-9 && d[2] > 0)) std::abort();
    } catch (const stochtex::Error&) {
    }
    return 0;
}
