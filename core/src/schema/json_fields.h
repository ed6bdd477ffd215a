// stochtex — strict access to JSON fields, for the .stex reader and the model parameter blocks.
//
// Every problem becomes a stochtex::Error of one format:
//   "<source>: <json path>: <problem>"     e.g. "t.stex: parameters.band_weights[1]: expected an
//                                                 array of numbers, got a string"
// so a user can find the offending field in the file. Reading is strict: a missing key, an
// unknown key, a wrong type or a wrong array size is an error, never a silent default.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace stochtex::json_fields {

/// Objects keep their key order: provenance options are stored in order, and the writer emits
/// keys in insertion order.
using Json = nlohmann::ordered_json;

/// Throws Error("<source>: <path>: <problem>"); an empty path stands for the top level.
[[noreturn]] void fail(const std::string& source, const std::string& path, const std::string& problem);

/// Parses JSON text. Beyond nlohmann's own checks (syntax errors, reported with line and column;
/// numbers that overflow to infinity) it rejects duplicate keys, which nlohmann would silently
/// resolve to one of the values.
Json parse(const std::string& text, const std::string& source);

/// A JSON value together with where it came from, so accessors can name it in errors.
/// Holds references: the Json tree and the source string must outlive the Field.
class Field {
public:
    /// The top level of a document read from `source`.
    Field(const Json& value, const std::string& source) : Field(value, source, std::string()) {}

    [[noreturn]] void fail(const std::string& problem) const;

    /// Requires an object whose keys are exactly `keys`, in any order, plus any of `optional`.
    void expect_keys(std::initializer_list<const char*> keys, std::initializer_list<const char*> optional = {}) const
    {
        expect_keys(std::vector<const char*>(keys), std::vector<const char*>(optional));
    }
    void expect_keys(const std::vector<const char*>& keys, const std::vector<const char*>& optional) const;
    /// Whether this object has the member `key` (for optional fields).
    bool contains(const char* key) const;
    /// The member `key` of this object (an error if this is not an object or lacks the key).
    Field operator[](const char* key) const;
    /// All members of this object, in file order.
    std::vector<std::pair<std::string, Field>> members() const;

    /// The elements of this array: exactly `expected_size` of them (called `noun` in the error)
    /// unless it is negative.
    std::vector<Field> elements(long expected_size = -1, const char* noun = "elements") const
    {
        return items("an array", expected_size, noun);
    }

    bool is_null() const { return value_->is_null(); }
    std::string string() const;
    bool boolean() const;
    double number() const;
    /// An integer token (no fraction or exponent) in [min, max].
    std::int64_t integer(std::int64_t min, std::int64_t max) const;
    /// An array of numbers of any length.
    std::vector<double> numbers() const;
    /// An array of exactly N numbers.
    template <std::size_t N>
    std::array<double, N> numbers() const
    {
        std::vector<Field> fields = items("an array of numbers", static_cast<long>(N), "numbers");
        std::array<double, N> result{};
        for (std::size_t i = 0; i < N; ++i) result[i] = fields[i].number();
        return result;
    }

private:
    Field(const Json& value, const std::string& source, std::string path)
        : value_(&value), source_(&source), path_(std::move(path)) {}
    /// Fails with "expected <wanted>, got <what this is>" unless `ok`.
    void expect(bool ok, const char* wanted) const;
    /// The elements of this array, described as `wanted` if it is not one; `expected_size`
    /// elements (named `noun` in the error) unless it is negative.
    std::vector<Field> items(const char* wanted, long expected_size, const char* noun) const;

    const Json* value_;
    const std::string* source_;
    std::string path_;
};

/// Writes `value` as canonical, human-readable JSON: two-space indentation, arrays of scalars on
/// one line, floating-point numbers as the shortest text that reads back as the same float (so
/// the text does not depend on digits below float precision), a final newline.
/// Every floating-point number must be finite and within float range (validate before writing).
std::string format(const Json& value);

}  // namespace stochtex::json_fields
