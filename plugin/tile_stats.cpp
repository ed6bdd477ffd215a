// stochtex — the plugin's per-file tile counts (tile_stats.h).
#include "tile_stats.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace stochtex::plugin {

namespace {

/// `text` as a JSON string (file names may hold quotes, backslashes or control characters).
std::string json_string(const std::string& text)
{
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
            out += escaped;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

}  // namespace

std::string tile_stats_line(const std::string& file, const TileCache& cache, const std::vector<LevelTiles>& levels)
{
    const std::vector<LevelTileCounts> counts = cache.counts();
    std::string line = "{\"file\": " + json_string(file) + ", \"tile_cache_bytes\": " + std::to_string(cache.max_bytes()) +
                       ", \"peak_bytes\": " + std::to_string(cache.peak_bytes()) + ", \"levels\": [";
    for (std::size_t level = 0; level < levels.size() && level < counts.size(); ++level) {
        if (level) line += ", ";
        line += "{\"level\": " + std::to_string(level) +
                ", \"tiles\": " + std::to_string(std::uint64_t(levels[level].across) * std::uint64_t(levels[level].down)) +
                ", \"made\": " + std::to_string(counts[level].made) + ", \"served\": " + std::to_string(counts[level].served) +
                "}";
    }
    return line + "]}\n";
}

void report_tile_stats(const std::string& file, const TileCache& cache, const std::vector<LevelTiles>& levels)
{
    const char* where = std::getenv("STOCHTEX_TILE_STATS");
    if (!where || !*where) return;
    const std::string line = tile_stats_line(file, cache, levels);
    if (std::string(where) == "-") {
        std::fputs(line.c_str(), stderr);
        return;
    }
    // A diagnostic: a file that cannot be written is said on stderr, never an error of the read.
    const int fd = ::open(where, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0 || ::write(fd, line.data(), line.size()) != ssize_t(line.size()))
        std::fprintf(stderr, "stex.imageio: cannot write tile counts to STOCHTEX_TILE_STATS=%s\n", where);
    if (fd >= 0) ::close(fd);
}

}  // namespace stochtex::plugin
