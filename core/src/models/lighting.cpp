#include <stochtex/error.h>
#include <stochtex/lighting.h>

#include "models/model.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace stochtex {

namespace {
std::string models_with_light()
{
    std::string names;
    for (const Model* model : registered_models())
        if (model->info().capabilities.light_direction) names += (names.empty() ? "" : ", ") + model->name();
    return names;
}
}  // namespace

bool depends_on_light(const TextureDescription& description)
{
    const Model* model = find_model(description.model);
    return model && model->info().capabilities.light_direction;
}

Vec3 light_direction(const TextureDescription& description)
{
    if (!depends_on_light(description))
        throw Error("model '" + description.model + "' does not depend on a light direction");
    return model_of(description).light(description);
}

void set_light_direction(TextureDescription& description, const Vec3& direction)
{
    if (!depends_on_light(description))
        throw Error("model '" + description.model + "' does not depend on a light direction (models that do: " +
                    models_with_light() + ")");
    const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    if (!std::isfinite(length) || !(length > 0)) throw Error("light direction: must be a finite, non-zero vector");
    if (!(direction[2] > 0)) throw Error("light direction: must point out of the surface (z > 0)");
    model_of(description).set_light(description, {direction[0] / length, direction[1] / length, direction[2] / length});
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
