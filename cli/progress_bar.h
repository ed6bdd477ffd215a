// A terminal progress bar on stderr; silent when stderr is not a terminal (logs, CI).
#pragma once

#include <stochtex/progress.h>

namespace stex_cli {

/// A callback that draws "stage [#####     ] 42%" in place; finishes the line at 100 %.
/// With machine-readable progress on (`stex --progress-lines`), it prints instead one line
/// "progress <fraction> <stage>" per percent to stderr, whatever stderr is: front-ends that run
/// stex as a subprocess (the Blender add-on) parse these.
stochtex::ProgressCallback terminal_progress_bar();
void set_progress_lines(bool enabled);
bool progress_lines_enabled();

}  // namespace stex_cli
