#include "batch_inputs.h"

#include <stochtex/error.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace stex_cli {

using stochtex::Error;
namespace fs = std::filesystem;

std::string batch_safe_name(const std::string& text)
{
    std::string name = text;
    for (char& c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_')) c = '_';
    if (name.empty() || name == "." || name == "..") name = "_" + name;
    return name;
}

namespace {

/// The extensions a folder's photos have (what read_image_linear reads through OpenImageIO);
/// anything else in the folder (notes, sidecars, the batch's own output) is left out.
bool is_photo_file(const fs::path& path)
{
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    static const char* const known[] = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".exr", ".hdr", ".bmp", ".tga", ".webp"};
    return std::find(std::begin(known), std::end(known), extension) != std::end(known);
}

std::vector<BatchPhoto> photos_of_folder(const fs::path& folder)
{
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file() && is_photo_file(entry.path())) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());  // byte order: the same on every host and locale
    std::vector<BatchPhoto> photos;
    for (const std::string& name : names) {
        BatchPhoto& photo = photos.emplace_back();
        photo.path = (folder / name).string();
        photo.listed_as = name;
        photo.name = batch_safe_name(fs::path(name).stem().string());
    }
    return photos;
}

/// RFC 4180 fields: commas separate, double quotes quote (a doubled quote is one quote).
std::vector<std::vector<std::string>> parse_csv(const std::string& text, const std::string& source)
{
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> row;
    std::string field;
    bool quoted = false, any = false;
    int line = 1;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
            else if (c == '"') quoted = false;
            else field += c, line += c == '\n';
            continue;
        }
        if (c == '"') quoted = any = true;
        else if (c == ',') row.push_back(field), field.clear(), any = true;
        else if (c == '\r') continue;
        else if (c == '\n') {
            if (any || !field.empty()) row.push_back(field), rows.push_back(row);
            row.clear(), field.clear(), any = false, ++line;
        } else field += c, any = true;
    }
    if (quoted) throw Error(source + ": line " + std::to_string(line) + ": a quoted field is not closed");
    if (any || !field.empty()) row.push_back(field), rows.push_back(row);
    return rows;
}

/// A manifest row's fields by column name (the header's, lower case).
using Row = std::map<std::string, std::string>;

std::vector<Row> rows_of_csv(const std::string& text, const std::string& source)
{
    const auto table = parse_csv(text, source);
    if (table.empty()) throw Error(source + ": empty manifest (a header row naming a 'photo' column is needed)");
    std::vector<std::string> header = table[0];
    for (std::string& column : header) {
        column.erase(0, column.find_first_not_of(" \t"));
        column.erase(column.find_last_not_of(" \t") + 1);
        std::transform(column.begin(), column.end(), column.begin(), [](unsigned char c) { return std::tolower(c); });
    }
    if (std::find(header.begin(), header.end(), "photo") == header.end())
        throw Error(source + ": the header row has no 'photo' column");
    std::vector<Row> rows;
    for (std::size_t r = 1; r < table.size(); ++r) {
        if (table[r].size() > header.size())
            throw Error(source + ": row " + std::to_string(r + 1) + " has " + std::to_string(table[r].size()) +
                        " fields, the header " + std::to_string(header.size()));
        Row& row = rows.emplace_back();
        for (std::size_t c = 0; c < table[r].size(); ++c) row[header[c]] = table[r][c];
    }
    return rows;
}

std::vector<Row> rows_of_json(const std::string& text, const std::string& source)
{
    nlohmann::json document;
    try {
        document = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(source + ": not valid JSON: " + e.what());
    }
    if (document.is_object() && document.contains("photos")) document = document["photos"];
    if (!document.is_array()) throw Error(source + ": expected an array of photos (or {\"photos\": [...]})");
    std::vector<Row> rows;
    for (std::size_t i = 0; i < document.size(); ++i) {
        const nlohmann::json& entry = document[i];
        const std::string where = source + ": photo " + std::to_string(i + 1);
        Row& row = rows.emplace_back();
        if (entry.is_string()) {
            row["photo"] = entry.get<std::string>();
            continue;
        }
        if (!entry.is_object()) throw Error(where + ": expected a file name or an object");
        for (const auto& [key, value] : entry.items()) {
            if (value.is_string()) row[key] = value.get<std::string>();
            else if (value.is_number()) row[key] = value.dump();
            else throw Error(where + ": '" + key + "' must be a string or a number");
        }
    }
    return rows;
}

std::vector<BatchPhoto> photos_of_manifest(const fs::path& manifest)
{
    const std::string source = manifest.string();
    std::ifstream file(manifest, std::ios::binary);
    if (!file) throw Error(source + ": cannot read the manifest");
    std::stringstream buffer;
    buffer << file.rdbuf();
    std::string extension = manifest.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    const std::vector<Row> rows =
        extension == ".json" ? rows_of_json(buffer.str(), source) : rows_of_csv(buffer.str(), source);
    static const char* const known_columns[] = {"photo", "name", "model", "colour", "color", "unit_size"};
    std::vector<BatchPhoto> photos;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& row = rows[i];
        const std::string where = source + ": photo " + std::to_string(i + 1);
        for (const auto& [key, value] : row)
            if (std::find(std::begin(known_columns), std::end(known_columns), key) == std::end(known_columns))
                throw Error(where + ": unknown field '" + key + "' (known: photo, name, model, colour, unit_size)");
        const auto field = [&](const char* key) {
            const auto found = row.find(key);
            return found == row.end() ? std::string() : found->second;
        };
        BatchPhoto& photo = photos.emplace_back();
        photo.listed_as = field("photo");
        if (photo.listed_as.empty()) throw Error(where + ": no 'photo'");
        const fs::path path(photo.listed_as);
        photo.path = (path.is_absolute() ? path : manifest.parent_path() / path).string();
        photo.name = batch_safe_name(field("name").empty() ? path.stem().string() : field("name"));
        photo.model = field("model");
        photo.colour = field("colour").empty() ? field("color") : field("colour");
        // unit_size is checked when the photo runs: a bad value fails that photo alone.
        const std::string unit_size = field("unit_size");
        if (!unit_size.empty()) {
            char* end = nullptr;
            photo.unit_size_m = std::strtod(unit_size.c_str(), &end);
            if (end == unit_size.c_str() || *end != '\0' || !(photo.unit_size_m > 0) || photo.unit_size_m > 1e6)
                photo.unit_size_m = -1;  // invalid: reported by the photo
        }
    }
    return photos;
}

}  // namespace

std::vector<BatchPhoto> list_batch_photos(const std::string& source)
{
    const fs::path path(source);
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (!fs::exists(status)) throw Error(source + ": no such folder or manifest");
    std::vector<BatchPhoto> photos = fs::is_directory(status) ? photos_of_folder(path) : photos_of_manifest(path);
    if (photos.empty()) throw Error(source + ": no photos (a folder's .png/.jpg/.tif/.exr files, or a manifest's rows)");
    std::map<std::string, std::size_t> first_of_name;
    for (std::size_t i = 0; i < photos.size(); ++i) {
        photos[i].index = int(i);
        const auto [at, fresh] = first_of_name.emplace(photos[i].name, i);
        if (!fresh)
            throw Error(source + ": photos " + std::to_string(at->second + 1) + " (" + photos[at->second].listed_as +
                        ") and " + std::to_string(i + 1) + " (" + photos[i].listed_as + ") have one output name '" +
                        photos[i].name + "'; give them names");
    }
    return photos;
}

}  // namespace stex_cli
