// stochtex — what a host asked the plugin for, per open file (docs/oiio-plugin.md).
//
// With STOCHTEX_TILE_STATS set, closing a .stex writes one JSON line: per MIP level the tiles
// it has, the tiles made and the tiles served from the tile cache. "-" writes to stderr, any
// other value is a file the line is appended to (one write, so concurrent readers and processes
// do not interleave). A host such as Blender gives no other way to see which tiles its texture
// cache streamed.
#pragma once

#include "tile_cache.h"

#include <string>
#include <vector>

namespace stochtex::plugin {

/// Tiles per level (ceil(width / tile width) x ceil(height / tile height)).
struct LevelTiles {
    int across = 0, down = 0;
};

/// The line for one file (exposed for the tests of its format).
std::string tile_stats_line(const std::string& file, const TileCache& cache, const std::vector<LevelTiles>& levels);
/// Writes the line where STOCHTEX_TILE_STATS says; nothing if it is unset or empty.
void report_tile_stats(const std::string& file, const TileCache& cache, const std::vector<LevelTiles>& levels);

}  // namespace stochtex::plugin
