// stochtex — the plugin's cache of recently made tiles, per open file (docs/oiio-plugin.md).
//
// Why: a host that keeps no tile cache of its own re-reads tiles. Cycles 5.2's texture cache
// reads each tile and then its 8 neighbours whole for a one-texel border, so a tile is asked
// for about 9 times; making it again each time costs the model's evaluation nine-fold. The
// cache keeps the most recently used tiles up to a byte budget and hands out copies, so what a
// reader gets is the same bytes whether the cache is on, off or evicting.
//
// It also counts, per MIP level, the tiles made and the tiles served from the cache: what a
// host asked for (STOCHTEX_TILE_STATS, tile_stats.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace stochtex::plugin {

/// What one MIP level was asked for.
struct LevelTileCounts {
    std::uint64_t made = 0;    // tiles made by the model (cache misses, or the cache off)
    std::uint64_t served = 0;  // tiles copied from the cache
};

/// Thread-safe least-recently-used tiles of one open file, at most `max_bytes` of texels
/// (0: keep none, count only).
class TileCache {
public:
    TileCache(std::size_t max_bytes, int levels);

    /// Copies the tile at (level, x, y) — `count` floats — to `out` and returns true if kept.
    bool copy(int level, int x, int y, float* out, std::size_t count);
    /// Records a tile just made (and keeps a copy if it fits the budget).
    void store(int level, int x, int y, const float* tile, std::size_t count);
    /// Records tiles made without the cache (blocks too large to go through it).
    void count_made(int level, std::uint64_t tiles);

    std::size_t max_bytes() const { return max_bytes_; }
    std::size_t peak_bytes() const;
    std::vector<LevelTileCounts> counts() const;

private:
    struct Key {
        int level, x, y;
        bool operator==(const Key& other) const { return level == other.level && x == other.x && y == other.y; }
    };
    struct KeyHash {
        std::size_t operator()(const Key& k) const
        {
            return std::hash<std::uint64_t>()((std::uint64_t(std::uint32_t(k.x)) << 32 | std::uint32_t(k.y)) ^
                                              (std::uint64_t(k.level) << 59));
        }
    };
    struct Entry {
        std::vector<float> texels;
        std::list<Key>::iterator age;  // position in recent_ (front: most recently used)
    };

    const std::size_t max_bytes_;
    mutable std::mutex mutex_;
    std::unordered_map<Key, Entry, KeyHash> tiles_;
    std::list<Key> recent_;
    std::size_t bytes_ = 0, peak_bytes_ = 0;
    std::vector<LevelTileCounts> counts_;
};

}  // namespace stochtex::plugin
