#include "schema/json_fields.h"

#include <stochtex/error.h>

#include <algorithm>
#include <charconv>
#include <limits>
#include <set>

namespace stochtex::json_fields {

namespace {

std::string describe(const Json& value)
{
    switch (value.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return "a boolean";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return "a number";
    case Json::value_t::string: return "a string";
    case Json::value_t::array: return "an array";
    case Json::value_t::object: return "an object";
    default: return "an unsupported value";
    }
}

std::string child_path(const std::string& path, const std::string& key)
{
    return path.empty() ? key : path + "." + key;
}

std::string child_path(const std::string& path, std::size_t index)
{
    return path + "[" + std::to_string(index) + "]";
}

/// nlohmann's messages start with "[json.exception.parse_error.101] "; users need only the rest.
std::string without_exception_id(const std::string& message)
{
    std::size_t end = message.find("] ");
    return end == std::string::npos ? message : message.substr(end + 2);
}

std::string float_text(double value)
{
    // Adding +0 turns -0 into 0: "-0" would read back as the integer 0 and then print as "0",
    // breaking byte identity on round trip.
    const float f = static_cast<float>(value) + 0.0f;
    char text[32];
    char* end = std::to_chars(text, text + sizeof text, f).ptr;
    // The reader parses the text as a double and the next write rounds that to float. For one
    // positive float (7.038531e-26, found by trying all of them) the double nearest to its
    // shortest text rounds to the neighbouring float; its exact value, as a double, does not.
    double parsed = 0;
    std::from_chars(text, end, parsed);
    if (static_cast<float>(parsed) != f) end = std::to_chars(text, text + sizeof text, static_cast<double>(f)).ptr;
    return std::string(text, end);
}

void write(std::string& out, const Json& value, int indent)
{
    const bool is_object = value.is_object();
    if (!is_object && !value.is_array()) {
        if (value.is_number_float())
            out += float_text(value.get<double>());
        else  // strings (escaped), integers, booleans, null
            out += value.dump(-1, ' ', false, Json::error_handler_t::replace);
        return;
    }
    const char* brackets = is_object ? "{}" : "[]";
    const bool nested = std::any_of(value.begin(), value.end(),
                                    [](const Json& item) { return item.is_structured(); });
    if (value.empty() || (!is_object && !nested)) {
        // Empty, or an array of scalars (a vector, a matrix row, a histogram): one line.
        out += brackets[0];
        for (auto item = value.begin(); item != value.end(); ++item) {
            if (item != value.begin()) out += ", ";
            write(out, *item, indent);
        }
        out += brackets[1];
        return;
    }
    const std::string inner(static_cast<std::size_t>(indent) + 2, ' ');
    out += brackets[0];
    for (auto item = value.begin(); item != value.end(); ++item) {
        out += item == value.begin() ? "\n" : ",\n";
        out += inner;
        if (is_object) out += Json(item.key()).dump(-1, ' ', false, Json::error_handler_t::replace) + ": ";
        write(out, item.value(), indent + 2);
    }
    out += "\n" + std::string(static_cast<std::size_t>(indent), ' ') + brackets[1];
}

}  // namespace

void fail(const std::string& source, const std::string& path, const std::string& problem)
{
    throw Error(source + ": " + (path.empty() ? "(top level)" : path) + ": " + problem);
}

Json parse(const std::string& text, const std::string& source)
{
    // Where the parser is, followed through its callbacks, so that a duplicate key or a number
    // overflow can be reported with the JSON path of the offending field.
    struct Level {
        bool is_object;
        std::set<std::string> keys;  // keys seen so far (objects)
        std::string key;             // the current member (objects)
        std::size_t index = 0;       // the current element (arrays)
    };
    std::vector<Level> levels;
    auto path = [&levels] {
        std::string result;
        for (const Level& level : levels)
            result = level.is_object ? child_path(result, level.key) : child_path(result, level.index);
        return result;
    };
    auto track = [&](int /*depth*/, nlohmann::detail::parse_event_t event, Json& parsed) {
        using Event = nlohmann::detail::parse_event_t;
        switch (event) {
        case Event::object_start: levels.push_back({true, {}, {}}); break;
        case Event::array_start: levels.push_back({false, {}, {}}); break;
        case Event::key:
            levels.back().key = parsed.get<std::string>();
            if (!levels.back().keys.insert(levels.back().key).second) fail(source, path(), "duplicate key");
            break;
        case Event::object_end:
        case Event::array_end:
            levels.pop_back();
            [[fallthrough]];  // a finished object or array is a value of its parent
        case Event::value:
            if (!levels.empty() && !levels.back().is_object) ++levels.back().index;
            break;
        }
        return true;
    };
    try {
        return Json::parse(text, track);
    } catch (const Json::parse_error& e) {
        throw Error(source + ": invalid JSON: " + without_exception_id(e.what()));
    } catch (const Json::out_of_range& e) {  // a number too large for a double, such as 1e999
        fail(source, path(), without_exception_id(e.what()));
    }
}

void Field::fail(const std::string& problem) const
{
    json_fields::fail(*source_, path_, problem);
}

void Field::expect(bool ok, const char* wanted) const
{
    if (!ok) fail(std::string("expected ") + wanted + ", got " + describe(*value_));
}

void Field::expect_keys(const std::vector<const char*>& keys, const std::vector<const char*>& optional) const
{
    expect(value_->is_object(), "an object");
    // Unknown keys first: a misspelt key is then reported as such, not as the missing one.
    auto listed = [](const std::vector<const char*>& list, const std::string& key) {
        return std::find(list.begin(), list.end(), key) != list.end();
    };
    for (auto member = value_->begin(); member != value_->end(); ++member) {
        if (listed(keys, member.key()) || listed(optional, member.key())) continue;
        std::string known;
        for (const char* key : keys) known += (known.empty() ? "" : ", ") + std::string(key);
        for (const char* key : optional) known += (known.empty() ? "" : ", ") + std::string(key) + " (optional)";
        json_fields::fail(*source_, child_path(path_, member.key()), "unknown field (expected one of: " + known + ")");
    }
    for (const char* key : keys) (*this)[key];
}

bool Field::contains(const char* key) const
{
    expect(value_->is_object(), "an object");
    return value_->contains(key);
}

Field Field::operator[](const char* key) const
{
    expect(value_->is_object(), "an object");
    auto member = value_->find(key);
    if (member == value_->end()) json_fields::fail(*source_, child_path(path_, key), "missing required field");
    return Field(*member, *source_, child_path(path_, key));
}

std::vector<std::pair<std::string, Field>> Field::members() const
{
    expect(value_->is_object(), "an object");
    std::vector<std::pair<std::string, Field>> result;
    for (auto member = value_->begin(); member != value_->end(); ++member)
        result.emplace_back(member.key(), Field(member.value(), *source_, child_path(path_, member.key())));
    return result;
}

std::vector<Field> Field::items(const char* wanted, long expected_size, const char* noun) const
{
    expect(value_->is_array(), wanted);
    if (expected_size >= 0 && value_->size() != static_cast<std::size_t>(expected_size))
        fail("expected " + std::to_string(expected_size) + " " + noun + ", got " + std::to_string(value_->size()));
    std::vector<Field> result;
    for (std::size_t i = 0; i < value_->size(); ++i)
        result.push_back(Field((*value_)[i], *source_, child_path(path_, i)));
    return result;
}

std::string Field::string() const
{
    expect(value_->is_string(), "a string");
    return value_->get<std::string>();
}

bool Field::boolean() const
{
    expect(value_->is_boolean(), "true or false");
    return value_->get<bool>();
}

double Field::number() const
{
    expect(value_->is_number(), "a number");
    return value_->get<double>();
}

std::int64_t Field::integer(std::int64_t min, std::int64_t max) const
{
    expect(value_->is_number(), "an integer");
    if (!value_->is_number_integer()) fail("expected an integer, got " + value_->dump());
    // Non-negative integers are stored unsigned and may exceed the int64 range.
    const bool too_large = value_->is_number_unsigned() &&
                           value_->get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max());
    const std::int64_t result = too_large ? 0 : value_->get<std::int64_t>();
    if (too_large || result < min || result > max)
        fail("expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + value_->dump());
    return result;
}

std::vector<double> Field::numbers() const
{
    std::vector<double> result;
    for (const Field& item : items("an array of numbers", -1, "numbers")) result.push_back(item.number());
    return result;
}

std::string format(const Json& value)
{
    std::string out;
    write(out, value, 0);
    out += '\n';
    return out;
}

}  // namespace stochtex::json_fields
