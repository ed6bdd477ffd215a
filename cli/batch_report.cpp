#include "batch_report.h"

#include "batch_gallery.h"

#include <stochtex/analysis.h>
#include <stochtex/atomic_write.h>
#include <stochtex/error.h>

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace stex_cli {

using stochtex::Error;
using stochtex::ModelScore;
using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

namespace {

// NaN (a metric that does not apply) is JSON null both ways.
Json number(double value) { return std::isnan(value) ? Json(nullptr) : Json(value); }
double number_of(const Json& value)
{
    return value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>();
}

Json score_json(const ModelScore& s)
{
    return Json{{"model", s.model},
                {"colour", s.colour},
                {"joint_colour", s.joint_colour},
                {"penalty", number(s.penalty)},
                {"radial_log_psd_db", number(s.radial_log_psd_db)},
                {"polar_log_psd_db", number(s.polar_log_psd_db)},
                {"w1_sigma", number(s.w1_sigma)},
                {"false_colour_rate", number(s.false_colour_rate)},
                {"gradient_orientation_degrees", number(s.gradient_orientation_degrees)},
                {"gradient_magnitude_w1", number(s.gradient_magnitude_w1)},
                {"bytes", s.bytes}};
}

ModelScore score_of(const Json& j)
{
    ModelScore s;
    s.model = j.at("model").get<std::string>();
    s.colour = j.at("colour").get<std::string>();
    s.joint_colour = j.at("joint_colour").get<bool>();
    s.penalty = number_of(j.at("penalty"));
    s.radial_log_psd_db = number_of(j.at("radial_log_psd_db"));
    s.polar_log_psd_db = number_of(j.at("polar_log_psd_db"));
    s.w1_sigma = number_of(j.at("w1_sigma"));
    s.false_colour_rate = number_of(j.at("false_colour_rate"));
    s.gradient_orientation_degrees = number_of(j.at("gradient_orientation_degrees"));
    s.gradient_magnitude_w1 = number_of(j.at("gradient_magnitude_w1"));
    s.bytes = j.at("bytes").get<long long>();
    return s;
}

Json record_json(const PhotoRecord& r, bool with_seconds)
{
    Json j{{"index", r.index}, {"name", r.name}, {"photo", r.photo}, {"status", r.status}, {"error", r.error},
           {"model", r.model}, {"colour", r.colour}, {"width", r.width}, {"height", r.height}, {"bytes", r.bytes}};
    // The chosen candidate's metrics at the top level, for readers that want one number each.
    j["chosen"] = r.chosen >= 0 ? score_json(r.candidates[r.chosen]) : Json(nullptr);
    Json& candidates = j["candidates"] = Json::array();
    for (const ModelScore& s : r.candidates) candidates.push_back(score_json(s));
    j["outputs"] = r.outputs;
    if (with_seconds) j["seconds"] = r.seconds;
    return j;
}

PhotoRecord record_of(const Json& j)
{
    PhotoRecord r;
    r.index = j.at("index").get<int>();
    r.name = j.at("name").get<std::string>();
    r.photo = j.at("photo").get<std::string>();
    r.status = j.at("status").get<std::string>();
    r.error = j.at("error").get<std::string>();
    r.model = j.at("model").get<std::string>();
    r.colour = j.at("colour").get<std::string>();
    r.width = j.at("width").get<int>();
    r.height = j.at("height").get<int>();
    r.bytes = j.at("bytes").get<long long>();
    for (const Json& s : j.at("candidates")) r.candidates.push_back(score_of(s));
    if (!j.at("chosen").is_null()) {
        const ModelScore chosen = score_of(j.at("chosen"));
        for (std::size_t i = 0; i < r.candidates.size(); ++i)
            if (r.candidates[i].model == chosen.model && r.candidates[i].colour == chosen.colour &&
                r.candidates[i].joint_colour == chosen.joint_colour)
                r.chosen = int(i);
    }
    r.outputs = j.at("outputs").get<std::vector<std::string>>();
    if (j.contains("seconds")) r.seconds = j.at("seconds").get<double>();
    return r;
}

std::string read_text(const fs::path& path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file) throw Error(path.string() + ": cannot read");
    std::stringstream buffer;
    buffer << file.rdbuf();
    return buffer.str();
}

std::string plan_text(const std::vector<BatchPhoto>& photos)
{
    Json plan{{"photos", Json::array()}};
    for (const BatchPhoto& p : photos) plan["photos"].push_back({{"index", p.index}, {"name", p.name}, {"photo", p.listed_as}});
    return plan.dump(1) + "\n";
}

/// A CSV field, quoted when it holds a separator, a quote or a line break.
std::string csv_field(const std::string& text)
{
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string csv_number(double value)
{
    if (std::isnan(value)) return "";
    return Json(value).dump();  // shortest round-trip form, as in report.json
}

std::string report_csv(const std::vector<PhotoRecord>& records)
{
    std::string text = "index,name,photo,status,model,colour,width,height,bytes,penalty,radial_log_psd_db,polar_log_psd_db,"
                       "w1_sigma,false_colour_rate,gradient_orientation_degrees,gradient_magnitude_w1,error\n";
    for (const PhotoRecord& r : records) {
        text += std::to_string(r.index) + "," + csv_field(r.name) + "," + csv_field(r.photo) + "," + r.status + "," +
                csv_field(r.model) + "," + csv_field(r.colour) + "," + std::to_string(r.width) + "," +
                std::to_string(r.height) + "," + std::to_string(r.bytes);
        const ModelScore* s = r.chosen >= 0 ? &r.candidates[r.chosen] : nullptr;
        for (double value : {s ? s->penalty : NAN, s ? s->radial_log_psd_db : NAN, s ? s->polar_log_psd_db : NAN,
                             s ? s->w1_sigma : NAN, s ? s->false_colour_rate : NAN,
                             s ? s->gradient_orientation_degrees : NAN, s ? s->gradient_magnitude_w1 : NAN})
            text += "," + csv_number(value);
        text += "," + csv_field(r.error) + "\n";
    }
    return text;
}

}  // namespace

void fill_from_description(PhotoRecord& record, const stochtex::TextureDescription& description)
{
    record.model = description.model;
    record.colour = stochtex::to_string(description.colour_mode);
    if (description.chroma_given_brightness.enabled()) record.colour += "+joint";
    record.candidates = description.provenance.model_choice;
    record.chosen = stochtex::chosen_model_score(description);
}

void write_batch_plan(const std::string& output_folder, const std::vector<BatchPhoto>& photos)
{
    const fs::path path = fs::path(output_folder) / "batch-plan.json";
    const std::string text = plan_text(photos);
    if (fs::exists(path) && read_text(path) != text)
        throw Error(output_folder + ": holds another batch (its batch-plan.json lists other photos); use a new output folder");
    stochtex::write_file_atomically(path.string(), text);
}

std::string shard_log_path(const std::string& output_folder, const std::string& shard_label)
{
    return (fs::path(output_folder) / "reports" / (shard_label + ".jsonl")).string();
}

void append_record(const std::string& log_path, const PhotoRecord& record)
{
    const std::string line = record_json(record, true).dump() + "\n";
    const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(log_path + ": cannot open the shard report: " + std::strerror(errno));
    const ssize_t written = ::write(fd, line.data(), line.size());
    const int write_error = errno;
    const bool synced = ::fsync(fd) == 0;
    ::close(fd);
    if (written != ssize_t(line.size()) || !synced)
        throw Error(log_path + ": cannot append to the shard report: " + std::strerror(write_error));
}

std::vector<PhotoRecord> read_shard_logs(const std::string& output_folder)
{
    const fs::path folder = fs::path(output_folder) / "reports";
    std::vector<fs::path> logs;
    if (fs::is_directory(folder))
        for (const fs::directory_entry& entry : fs::directory_iterator(folder))
            if (entry.path().extension() == ".jsonl") logs.push_back(entry.path());
    std::sort(logs.begin(), logs.end());
    std::vector<PhotoRecord> records;
    for (const fs::path& log : logs) {
        const std::string text = read_text(log);
        std::size_t start = 0, line_number = 1;
        for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1, ++line_number) {
            try {
                records.push_back(record_of(Json::parse(text.substr(start, end - start))));
            } catch (const nlohmann::json::exception& e) {
                throw Error(log.string() + ": line " + std::to_string(line_number) + ": not a batch record: " + e.what());
            }
        }
    }
    return records;
}

std::vector<std::string> finished_names(const std::string& output_folder)
{
    std::vector<std::string> names;
    for (const PhotoRecord& r : read_shard_logs(output_folder))
        if (r.status == "done") names.push_back(r.name);
    return names;
}

MergeSummary merge_batch_reports(const std::string& output_folder)
{
    const fs::path plan_path = fs::path(output_folder) / "batch-plan.json";
    if (!fs::exists(plan_path))
        throw Error(output_folder + ": no batch-plan.json: not the output folder of a stex batch");
    const Json plan = Json::parse(read_text(plan_path));
    std::vector<PhotoRecord> merged;
    std::map<std::string, std::size_t> by_name;
    for (const Json& p : plan.at("photos")) {
        PhotoRecord& r = merged.emplace_back();
        r.index = p.at("index").get<int>();
        r.name = p.at("name").get<std::string>();
        r.photo = p.at("photo").get<std::string>();
        r.status = "missing";
        r.error = "no shard reported this photo";
        by_name[r.name] = merged.size() - 1;
    }
    for (const PhotoRecord& r : read_shard_logs(output_folder)) {
        const auto at = by_name.find(r.name);
        if (at == by_name.end()) continue;  // not of this batch
        PhotoRecord& kept = merged[at->second];
        if (kept.status != "done") kept = r;  // a done record stays; a later failure replaces an earlier one
    }
    MergeSummary summary;
    summary.total = int(merged.size());
    Json photos = Json::array();
    std::string timings = "index,name,status,seconds\n";
    for (const PhotoRecord& r : merged) {
        summary.done += r.status == "done";
        summary.failed += r.status == "failed";
        summary.missing += r.status == "missing";
        photos.push_back(record_json(r, false));
        timings += std::to_string(r.index) + "," + csv_field(r.name) + "," + r.status + "," + Json(r.seconds).dump() + "\n";
    }
    const Json report{{"summary", {{"photos", summary.total}, {"done", summary.done}, {"failed", summary.failed},
                                   {"missing", summary.missing}}},
                      {"photos", photos}};
    const fs::path folder(output_folder);
    stochtex::write_file_atomically((folder / "report.json").string(), report.dump(1) + "\n");
    stochtex::write_file_atomically((folder / "report.csv").string(), report_csv(merged));
    stochtex::write_file_atomically((folder / "timings.csv").string(), timings);
    stochtex::write_file_atomically((folder / "index.html").string(), gallery_html(merged));
    return summary;
}

}  // namespace stex_cli
