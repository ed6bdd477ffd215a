#include <stochtex/error.h>
#include <stochtex/lighting.h>

#include <charconv>
#include <cmath>
#include <sstream>

namespace stochtex {

bool depends_on_light(const TextureDescription& description) { return description.ptm.has_value(); }

Vec3 light_direction(const TextureDescription& description)
{
    if (!description.ptm) throw Error("model '" + description.model + "' does not depend on a light direction");
    return description.ptm->light;
}

void set_light_direction(TextureDescription& description, const Vec3& direction)
{
    if (!description.ptm)
        throw Error("model '" + description.model + "' does not depend on a light direction (only ptm does)");
    const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    if (!std::isfinite(length) || !(length > 0)) throw Error("light direction: must be a finite, non-zero vector");
    if (!(direction[2] > 0)) throw Error("light direction: must point out of the surface (z > 0)");
    description.ptm->light = {direction[0] / length, direction[1] / length, direction[2] / length};
}

Vec3 parse_light_direction(const std::string& text)
{
    std::string spaced = text;
    for (char& c : spaced)
        if (c == ',') c = ' ';
    std::istringstream in(spaced);
    std::string field;
    Vec3 direction{};
    int count = 0;
    while (in >> field) {
        double value = 0;
        const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
        if (error != std::errc() || end != field.data() + field.size() || count == 3)
            throw Error("light direction: expected three numbers 'x,y,z', got '" + text + "'");
        direction[count++] = value;
    }
    if (count != 3) throw Error("light direction: expected three numbers 'x,y,z', got '" + text + "'");
    const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    if (!std::isfinite(length) || !(length > 0)) throw Error("light direction: must be a finite, non-zero vector, got '" + text + "'");
    if (!(direction[2] > 0)) throw Error("light direction: must point out of the surface (z > 0), got '" + text + "'");
    return {direction[0] / length, direction[1] / length, direction[2] / length};
}

}  // namespace stochtex
