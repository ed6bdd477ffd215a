// A terminal progress bar on stderr; silent when stderr is not a terminal (logs, CI).
#pragma once

#include <stochtex/progress.h>

namespace stex_cli {

/// A callback that draws "stage [#####     ] 42%" in place; finishes the line at 100 %.
stochtex::ProgressCallback terminal_progress_bar();

}  // namespace stex_cli
