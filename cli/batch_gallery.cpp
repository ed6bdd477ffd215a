#include "batch_gallery.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stex_cli {

using stochtex::ModelScore;

namespace {

std::string escaped(const std::string& text)
{
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        case '\'': out += "&#39;"; break;
        default: out += c;
        }
    }
    return out;
}

std::string fixed(double value, const char* format)
{
    if (std::isnan(value)) return "n/a";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, format, value);
    return buffer;
}

bool has_output(const PhotoRecord& r, const std::string& file) { return std::find(r.outputs.begin(), r.outputs.end(), file) != r.outputs.end(); }

std::string score_table(const PhotoRecord& r)
{
    std::string html = "<table class=scores><tr><th>model</th><th>colour</th><th>penalty</th><th>radial dB</th><th>2D dB</th>"
                       "<th>W1/&sigma;</th><th>false colour</th><th>orient. &deg;</th><th>|&nabla;| W1</th><th>bytes</th></tr>";
    for (std::size_t i = 0; i < r.candidates.size(); ++i) {
        const ModelScore& s = r.candidates[i];
        html += std::string("<tr") + (int(i) == r.chosen ? " class=chosen" : "") + "><td>" + escaped(s.model) + "</td><td>" +
                escaped(s.colour + (s.joint_colour ? "+joint" : "")) + "</td><td>" + fixed(s.penalty, "%.3f") + "</td><td>" +
                fixed(s.radial_log_psd_db, "%.2f") + "</td><td>" + fixed(s.polar_log_psd_db, "%.2f") + "</td><td>" +
                fixed(s.w1_sigma, "%.3f") + "</td><td>" + fixed(100 * s.false_colour_rate, "%.2f") + " %</td><td>" +
                fixed(s.gradient_orientation_degrees, "%.2f") + "</td><td>" + fixed(s.gradient_magnitude_w1, "%.3f") +
                "</td><td>" + std::to_string(s.bytes) + "</td></tr>";
    }
    return html + "</table>";
}

const char* const page_head = R"(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>stex batch</title>
<style>
body { font: 14px/1.4 sans-serif; margin: 1.5em; color: #222; }
table.batch { border-collapse: collapse; }
table.batch > tbody > tr > td, table.batch > thead > tr > th { border-bottom: 1px solid #ccc; padding: 6px 8px; vertical-align: top; text-align: left; }
table.batch > thead th { cursor: pointer; background: #eee; user-select: none; }
table.batch > thead th.sorted::after { content: " \25BE"; }
tr.failed, tr.missing { background: #fde8e8; }
div.pair { display: flex; gap: 4px; }
img { width: 128px; height: 128px; object-fit: cover; background: #ddd; }
.missing-image { outline: 3px solid #c00; }
table.scores { border-collapse: collapse; font-size: 12px; margin-top: 4px; }
table.scores td, table.scores th { padding: 1px 6px; text-align: right; border: 0; }
table.scores tr.chosen { font-weight: bold; background: #e6f2e6; }
.penalty { font-size: 18px; font-weight: bold; }
.error { color: #a00; white-space: pre-wrap; max-width: 40em; }
</style></head><body>
<h1>stex batch</h1>
<p id=summary></p>
<p>Photo (left) and synthesis (right), top-left crops at the photo's pixel scale. Click a column to sort; the page opens worst penalty first (failures on top).</p>
<table class=batch><thead><tr><th data-key=index>#</th><th data-key=name>photo</th><th>photo | synthesis</th><th data-key=model>model</th><th data-key=penalty class=sorted>penalty</th><th data-key=bytes>bytes</th><th>scores</th><th>files</th></tr></thead>
<tbody>
)";

const char* const page_tail = R"(</tbody></table>
<script>
"use strict";
(function () {
  const body = document.querySelector("table.batch tbody");
  const rows = Array.from(body.rows);
  const counts = {};
  rows.forEach(r => { counts[r.dataset.status] = (counts[r.dataset.status] || 0) + 1; });
  document.getElementById("summary").textContent = rows.length + " photos: " +
    Object.keys(counts).sort().map(k => counts[k] + " " + k).join(", ");
  // Failed and missing photos sort as the worst: an infinite penalty.
  const value = (row, key) => {
    const text = row.dataset[key];
    if (key === "name" || key === "model") return text;
    return text === "" ? Infinity : Number(text);
  };
  let current = "penalty", descending = true;
  function sort(key) {
    descending = key === current ? !descending : (key === "penalty" || key === "bytes");
    current = key;
    rows.sort((a, b) => {
      const x = value(a, key), y = value(b, key);
      const order = x < y ? -1 : x > y ? 1 : Number(a.dataset.index) - Number(b.dataset.index);
      return descending ? -order : order;
    });
    rows.forEach(r => body.appendChild(r));
    document.querySelectorAll("table.batch thead th").forEach(th => th.classList.toggle("sorted", th.dataset.key === key));
  }
  document.querySelectorAll("table.batch thead th[data-key]").forEach(th => th.addEventListener("click", () => sort(th.dataset.key)));
  descending = false; sort("penalty");
  // An image that does not load is marked, so that a reviewer (and the browser test) sees it.
  function mark(img) { img.classList.add("missing-image"); img.closest("tr").classList.add("missing-image-row"); img.alt = "missing: " + img.getAttribute("src"); }
  document.querySelectorAll("img").forEach(img => {
    if (img.complete && img.naturalWidth === 0) mark(img);
    img.addEventListener("error", () => mark(img));
  });
})();
</script>
</body></html>
)";

}  // namespace

std::string gallery_html(const std::vector<PhotoRecord>& records)
{
    std::string html = page_head;
    for (const PhotoRecord& r : records) {
        const ModelScore* chosen = r.chosen >= 0 ? &r.candidates[r.chosen] : nullptr;
        const std::string folder = r.name + "/";
        // Penalty as data: empty for a failed photo or a named model (no score table), which sorts as the worst.
        const std::string penalty = chosen && !std::isnan(chosen->penalty) ? fixed(chosen->penalty, "%.6f") : "";
        html += "<tr class=\"" + escaped(r.status) + "\" data-status=\"" + escaped(r.status) + "\" data-index=" +
                std::to_string(r.index) + " data-name=\"" + escaped(r.name) + "\" data-model=\"" + escaped(r.model) +
                "\" data-penalty=\"" + penalty + "\" data-bytes=\"" + (r.status == "done" ? std::to_string(r.bytes) : "") +
                "\">\n<td>" + std::to_string(r.index) + "</td><td>" + escaped(r.name) + "<br><small>" + escaped(r.photo) +
                (r.width ? "<br>" + std::to_string(r.width) + "&times;" + std::to_string(r.height) : "") + "</small></td><td><div class=pair>";
        for (const char* image : {"photo.png", "synthesis.png"})
            if (has_output(r, folder + image))
                html += "<img src=\"" + escaped(folder + image) + "\" alt=\"" + escaped(r.name + " " + image) + "\">";
        html += "</div></td><td>" + escaped(r.model) + "<br><small>" + escaped(r.colour) + "</small></td><td class=penalty>" +
                (penalty.empty() ? std::string("&ndash;") : fixed(chosen->penalty, "%.3f")) + "</td><td>" +
                (r.status == "done" ? std::to_string(r.bytes) : "") + "</td><td>";
        if (r.status != "done") html += "<div class=error>" + escaped(r.status + ": " + r.error) + "</div>";
        else if (r.candidates.empty()) html += "(model named: no score table)";
        else html += score_table(r);
        html += "</td><td>";
        for (const std::string& file : r.outputs)
            if (file.size() < 4 || (file.compare(file.size() - 4, 4, ".png") != 0 || file == folder + "compare.png"))
                html += "<a href=\"" + escaped(file) + "\">" + escaped(file.substr(folder.size())) + "</a><br>";
        html += "</td></tr>\n";
    }
    return html + page_tail;
}

}  // namespace stex_cli
