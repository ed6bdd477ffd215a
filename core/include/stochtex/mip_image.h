// stochtex — a texture presented as a tiled, MIP-mapped image (the OIIO plugin, baked maps).
//
// Level 0 is exactly one period of the periodic texture (make_periodic_texture) at the
// layout's size and scale, so the image wraps without a seam. Level l is max(1, size >> l) on
// each axis, down to 1 × 1. Every texel of every level is evaluated by the model with the
// footprint of that level's texel (its spacing in u and in v): the model's own filter, not a
// box-filtered copy of the level below. The 1 × 1 level is therefore the texture's mean.
#pragma once

#include <stochtex/texture.h>

#include <memory>

namespace stochtex {

class MipImage {
public:
    /// Throws Error if the description or the layout is invalid (`source` names them).
    MipImage(const TextureDescription& description, const ImageLayout& layout, const std::string& source);

    const ImageLayout& layout() const { return layout_; }
    int level_count() const { return int(level_sizes_.size()); }
    int level_width(int level) const { return level_sizes_.at(level)[0]; }
    int level_height(int level) const { return level_sizes_.at(level)[1]; }
    /// 3 (RGB), 4 (RGBA, alpha 1) or 1 (Y, Rec.709 luminance), per layout().channels.
    int channel_count() const { return channel_count_; }
    /// Texture units covered by the whole image (the texture's period).
    const Vec2& period() const { return period_; }

    /// Fills texels [x0, x0 + w) × [y0, y0 + h) of `level` (inside the level) into `out`:
    /// channel_count() floats per texel, rows of `w` texels, top row first. Thread-safe;
    /// bit-identical results whatever the thread or call order.
    void fill(int level, int x0, int y0, int w, int h, float* out) const;

    const Texture& texture() const { return *texture_; }

private:
    ImageLayout layout_;
    Vec2 period_{};
    int channel_count_ = 3;
    std::vector<std::array<int, 2>> level_sizes_;
    std::unique_ptr<Texture> texture_;
};

}  // namespace stochtex
