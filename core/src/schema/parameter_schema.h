// One declaration of a parameter struct's fields — key, type, range, default, unit, doc — from
// which its .stex block is read (strictly: unknown, missing and mistyped keys are errors naming
// the JSON path), written (keys in declaration order, so files stay canonical), validated, and
// documented (ParameterInfo: `stex --list-models --json`, the tables of docs/stex-format.md).
//
// A model declares its schema once, in its folder (models/<name>/<name>_model.cpp):
//
//   ParameterSchema<GaborParameters> schema;
//   schema.number("bandwidth", &GaborParameters::bandwidth, {1.0 / 16, 16},
//                 {"1", "", "a / F: kernel bandwidth relative to the octave's frequency"});
//
// Simple fields (numbers, integers, booleans, enumerations, fixed and per-channel arrays,
// nested objects and lists of objects) need nothing more; a field whose encoding is special
// (an embedded PNG, a file beside the .stex) supplies its own reader, writer and checks with
// custom(). Checks that relate several fields are added with check().
#pragma once

#include "schema/json_fields.h"

#include <stochtex/model.h>

#include <array>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace stochtex {

/// The text of a number in messages and documentation: the shortest that reads back exactly.
inline std::string number_text(double value)
{
    char text[32];
    return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

/// Where a field is in a file: "parameters.strata[2].spacing".
inline std::string json_path(const std::string& parent, const std::string& key)
{
    return parent.empty() ? key : parent + "." + key;
}
inline std::string json_path(const std::string& parent, std::size_t index)
{
    return parent + "[" + std::to_string(index) + "]";
}

/// The finiteness every stored number needs: numbers are stored as floats, so they must be
/// finite as floats. (A negated comparison, so that NaN fails it.)
inline void check_float_finite(double value, const std::string& path, const std::string& source)
{
    if (!(std::fabs(value) <= std::numeric_limits<float>::max()))
        json_fields::fail(source, path, "expected a finite number within float range, got " + number_text(value));
}

/// An inclusive range of numbers; `unit` is named after the range in messages.
struct NumberRange {
    double min = -std::numeric_limits<float>::max();
    double max = std::numeric_limits<float>::max();
    std::string unit;
    bool bounded() const { return min > -std::numeric_limits<float>::max() || max < std::numeric_limits<float>::max(); }
    std::string text() const { return "[" + number_text(min) + ", " + number_text(max) + "]"; }
};

inline void check_in_range(double value, const NumberRange& range, const std::string& path, const std::string& source)
{
    check_float_finite(value, path, source);
    if (!(value >= range.min && value <= range.max))
        json_fields::fail(source, path,
                          "must be in " + range.text() + (range.unit.empty() ? "" : " " + range.unit) + ", got " +
                              number_text(value));
}

/// The documentation of one field: default (as text; "" when none applies), unit, its meaning
/// and constraints, and (optionally) the allowed values in words when the declared range does
/// not say it all (e.g. "a power of two in [4, 4096]").
struct FieldDoc {
    std::string default_value;
    std::string unit;
    std::string doc;
    std::string range = {};
};

/// What a reader may need beyond the JSON: where the .stex is (files kept beside it).
struct ReadContext {
    std::string stex_path;
};

template <class Struct>
class ParameterSchema {
public:
    using Json = json_fields::Json;
    using Field = json_fields::Field;
    /// Checks a whole struct; `path` is where it is in the file ("parameters").
    using Check = std::function<void(const Struct&, const std::string& path, const std::string& source)>;

    /// A field with its own encoding. `read` fills the struct from the field's value; `write`
    /// returns the value to store; `validate` checks it (path: the field's own path).
    ParameterSchema& custom(ParameterInfo info, std::function<void(const Field&, Struct&, const ReadContext&)> read,
                            std::function<Json(const Struct&)> write, Check validate = {})
    {
        entries_.push_back({std::move(info), false, {}, std::move(read), std::move(write), std::move(validate)});
        return *this;
    }
    /// Like custom(), for a key that may be absent: `present` tells whether the struct has it
    /// (absent keys are not written, and `read` is called only when the key is there).
    ParameterSchema& optional_custom(ParameterInfo info, std::function<bool(const Struct&)> present,
                                     std::function<void(const Field&, Struct&, const ReadContext&)> read,
                                     std::function<Json(const Struct&)> write, Check validate = {})
    {
        info.optional = true;
        entries_.push_back(
            {std::move(info), true, std::move(present), std::move(read), std::move(write), std::move(validate)});
        return *this;
    }

    ParameterSchema& number(const char* key, double Struct::*member, NumberRange range, FieldDoc doc, Check extra = {})
    {
        ParameterInfo info = make_info(key, "number", range.bounded() ? range.text() : "finite", doc);
        return custom(
            info, [member](const Field& f, Struct& s, const ReadContext&) { s.*member = f.number(); },
            [member](const Struct& s) { return Json(s.*member); },
            [member, range, extra](const Struct& s, const std::string& path, const std::string& source) {
                check_in_range(s.*member, range, path, source);
                if (extra) extra(s, path, source);
            });
    }

    template <class Integer>
    ParameterSchema& integer(const char* key, Integer Struct::*member, std::int64_t min, std::int64_t max, FieldDoc doc,
                             Check extra = {})
    {
        ParameterInfo info = make_info(key, "integer", "[" + std::to_string(min) + ", " + std::to_string(max) + "]", doc);
        return custom(
            info, [member, min, max](const Field& f, Struct& s, const ReadContext&) { s.*member = Integer(f.integer(min, max)); },
            [member](const Struct& s) { return Json(s.*member); }, extra);
    }

    ParameterSchema& boolean(const char* key, bool Struct::*member, FieldDoc doc)
    {
        return custom(make_info(key, "boolean", "true | false", doc),
                      [member](const Field& f, Struct& s, const ReadContext&) { s.*member = f.boolean(); },
                      [member](const Struct& s) { return Json(s.*member); });
    }

    /// A string (`extra` checks its value).
    ParameterSchema& text(const char* key, std::string Struct::*member, FieldDoc doc, Check extra = {})
    {
        return custom(make_info(key, "string", "", doc),
                      [member](const Field& f, Struct& s, const ReadContext&) { s.*member = f.string(); },
                      [member](const Struct& s) { return Json(s.*member); }, std::move(extra));
    }

    /// An enumeration stored as its name; `from_string` throws Error for unknown names.
    template <class Enum>
    ParameterSchema& enumeration(const char* key, Enum Struct::*member, const char* (*to_string)(Enum),
                                 Enum (*from_string)(const std::string&), std::vector<Enum> values, FieldDoc doc)
    {
        std::string names;
        for (Enum value : values) names += (names.empty() ? "" : " | ") + std::string(to_string(value));
        return custom(
            make_info(key, "string", names, doc),
            [member, from_string](const Field& f, Struct& s, const ReadContext&) {
                try {
                    s.*member = from_string(f.string());
                } catch (const std::exception& e) {
                    f.fail(e.what());
                }
            },
            [member, to_string](const Struct& s) { return Json(to_string(s.*member)); });
    }

    /// Exactly N numbers, each finite (and in `range` when it is bounded).
    template <std::size_t N>
    ParameterSchema& numbers(const char* key, std::array<double, N> Struct::*member, NumberRange range, FieldDoc doc,
                             Check extra = {})
    {
        ParameterInfo info = make_info(key, "array of " + std::to_string(N) + " numbers", range.bounded() ? range.text() : "finite", doc);
        return custom(
            info, [member](const Field& f, Struct& s, const ReadContext&) { s.*member = f.numbers<N>(); },
            [member](const Struct& s) { return Json(s.*member); },
            [member, range, extra](const Struct& s, const std::string& path, const std::string& source) {
                for (std::size_t i = 0; i < N; ++i) check_in_range((s.*member)[i], range, json_path(path, i), source);
                if (extra) extra(s, path, source);
            });
    }

    /// Numbers of any count (`extra` checks the count and the values).
    ParameterSchema& numbers(const char* key, std::vector<double> Struct::*member, FieldDoc doc, Check extra = {})
    {
        return custom(
            make_info(key, "array of numbers", "", doc), [member](const Field& f, Struct& s, const ReadContext&) { s.*member = f.numbers(); },
            [member](const Struct& s) { return Json(s.*member); }, extra);
    }

    /// Three arrays of numbers, one per decorrelated channel (`extra` checks counts and values).
    ParameterSchema& channel_numbers(const char* key, std::array<std::vector<double>, 3> Struct::*member, FieldDoc doc,
                                     Check extra = {})
    {
        return custom(
            make_info(key, "3 arrays of numbers", "", doc),
            [member](const Field& f, Struct& s, const ReadContext&) {
                std::vector<Field> channels = f.elements(3, "channels");
                for (std::size_t c = 0; c < 3; ++c) (s.*member)[c] = channels[c].numbers();
            },
            [member](const Struct& s) { return Json(s.*member); }, extra);
    }

    /// An object described by its own schema.
    template <class Sub>
    ParameterSchema& object(const char* key, Sub Struct::*member, const ParameterSchema<Sub>& sub, FieldDoc doc)
    {
        ParameterInfo info = make_info(key, "object", "", doc);
        info.fields = sub.infos();
        return custom(
            info, [member, sub](const Field& f, Struct& s, const ReadContext& context) { s.*member = sub.read(f, context); },
            [member, sub](const Struct& s) { return sub.write(s.*member); },
            [member, sub](const Struct& s, const std::string& path, const std::string& source) {
                sub.validate(s.*member, path, source);
            });
    }

    /// A list of objects, each described by `sub`; `extra` checks the count.
    template <class Sub>
    ParameterSchema& list(const char* key, std::vector<Sub> Struct::*member, const ParameterSchema<Sub>& sub, FieldDoc doc,
                          Check extra = {})
    {
        ParameterInfo info = make_info(key, "array of objects", "", doc);
        info.fields = sub.infos();
        return custom(
            info,
            [member, sub](const Field& f, Struct& s, const ReadContext& context) {
                for (const Field& element : f.elements()) (s.*member).push_back(sub.read(element, context));
            },
            [member, sub](const Struct& s) {
                Json array = Json::array();
                for (const Sub& element : s.*member) array.push_back(sub.write(element));
                return array;
            },
            [member, sub, extra](const Struct& s, const std::string& path, const std::string& source) {
                if (extra) extra(s, path, source);
                for (std::size_t i = 0; i < (s.*member).size(); ++i) sub.validate((s.*member)[i], json_path(path, i), source);
            });
    }

    /// Makes the field declared last optional: written only where `present` says the struct has
    /// it, read and checked only where the key is there (e.g. a list written only when not empty).
    ParameterSchema& optional_when(std::function<bool(const Struct&)> present)
    {
        Entry& last = entries_.back();
        last.info.optional = true;
        last.optional = true;
        last.present = std::move(present);
        return *this;
    }

    /// A check relating several fields, run after the fields' own checks.
    ParameterSchema& check(Check whole)
    {
        checks_.push_back(std::move(whole));
        return *this;
    }

    // ---- What the declaration drives ----------------------------------------------------------

    /// Reads an object holding exactly the declared keys (optional ones may be absent).
    Struct read(const Field& block, const ReadContext& context = {}) const
    {
        Struct result{};
        read_into(block, result, context);
        return result;
    }

    /// Like read(), into an existing struct: the keys present are set, the others keep their
    /// values (a block that declares some of a larger struct's members, or defaults overridden).
    void read_into(const Field& block, Struct& result, const ReadContext& context = {}) const
    {
        std::vector<const char*> required, optional;
        for (const Entry& entry : entries_) (entry.optional ? optional : required).push_back(entry.info.key.c_str());
        block.expect_keys(required, optional);
        for (const Entry& entry : entries_)
            if (!entry.optional || block.contains(entry.info.key.c_str())) entry.read(block[entry.info.key.c_str()], result, context);
    }

    /// The object to store: keys in declaration order.
    Json write(const Struct& value) const
    {
        Json json = Json::object();
        for (const Entry& entry : entries_)
            if (!entry.optional || entry.present(value)) json[entry.info.key] = entry.write(value);
        return json;
    }

    /// Every field's checks in declaration order, then the whole-struct checks; errors name
    /// `source` and the field's path below `path`.
    void validate(const Struct& value, const std::string& path, const std::string& source) const
    {
        for (const Entry& entry : entries_)
            if (entry.validate && (!entry.optional || entry.present(value)))
                entry.validate(value, json_path(path, entry.info.key), source);
        for (const Check& whole : checks_) whole(value, path, source);
    }

    std::vector<ParameterInfo> infos() const
    {
        std::vector<ParameterInfo> result;
        for (const Entry& entry : entries_) result.push_back(entry.info);
        return result;
    }

private:
    struct Entry {
        ParameterInfo info;
        bool optional;
        std::function<bool(const Struct&)> present;
        std::function<void(const Field&, Struct&, const ReadContext&)> read;
        std::function<Json(const Struct&)> write;
        Check validate;
    };
    static ParameterInfo make_info(const char* key, std::string type, std::string range, const FieldDoc& doc)
    {
        return {key, std::move(type), doc.range.empty() ? std::move(range) : doc.range, doc.default_value, doc.unit, doc.doc,
                {}, false};
    }

    std::vector<Entry> entries_;
    std::vector<Check> checks_;
};

}  // namespace stochtex
