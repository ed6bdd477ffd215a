// stochtex — the plugin's cache of recently made tiles (tile_cache.h).
#include "tile_cache.h"

#include <algorithm>

namespace stochtex::plugin {

TileCache::TileCache(std::size_t max_bytes, int levels) : max_bytes_(max_bytes), counts_(std::size_t(levels)) {}

bool TileCache::copy(int level, int x, int y, float* out, std::size_t count)
{
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto found = tiles_.find(Key{level, x, y});
    if (found == tiles_.end() || found->second.texels.size() != count) return false;
    recent_.splice(recent_.begin(), recent_, found->second.age);
    std::copy(found->second.texels.begin(), found->second.texels.end(), out);
    ++counts_[std::size_t(level)].served;
    return true;
}

void TileCache::store(int level, int x, int y, const float* tile, std::size_t count)
{
    const std::size_t bytes = count * sizeof(float);
    const std::lock_guard<std::mutex> lock(mutex_);
    ++counts_[std::size_t(level)].made;
    if (bytes > max_bytes_) return;
    const Key k{level, x, y};
    if (tiles_.count(k)) return;  // another thread made it meanwhile: the same texels
    while (bytes_ + bytes > max_bytes_) {
        const auto oldest = tiles_.find(recent_.back());
        bytes_ -= oldest->second.texels.size() * sizeof(float);
        tiles_.erase(oldest);
        recent_.pop_back();
    }
    recent_.push_front(k);
    tiles_.emplace(k, Entry{std::vector<float>(tile, tile + count), recent_.begin()});
    bytes_ += bytes;
    peak_bytes_ = std::max(peak_bytes_, bytes_);
}

void TileCache::count_made(int level, std::uint64_t tiles)
{
    const std::lock_guard<std::mutex> lock(mutex_);
    counts_[std::size_t(level)].made += tiles;
}

std::size_t TileCache::peak_bytes() const
{
    const std::lock_guard<std::mutex> lock(mutex_);
    return peak_bytes_;
}

std::vector<LevelTileCounts> TileCache::counts() const
{
    const std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
}

}  // namespace stochtex::plugin
