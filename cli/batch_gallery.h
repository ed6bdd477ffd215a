// `stex batch`: index.html, a static page to review a batch (no server, no external assets).
#pragma once

#include "batch_report.h"

#include <string>
#include <vector>

namespace stex_cli {

/// The gallery of `records` (in index order; the page sorts itself, worst penalty first, and by
/// any column clicked): per photo its crop and the synthesis at the same pixel scale, the model,
/// the score table, links to the .stex, compare figure and bake. Links are relative: the page
/// sits in the batch's output folder and works from disk. An image that fails to load is marked
/// "missing" on the page (class "missing"), which the browser test looks for.
std::string gallery_html(const std::vector<PhotoRecord>& records);

}  // namespace stex_cli
