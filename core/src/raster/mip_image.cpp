#include <stochtex/error.h>
#include <stochtex/mip_image.h>
#include <stochtex/stex_file.h>

#include <vector>

namespace stochtex {

MipImage::MipImage(const TextureDescription& description, const ImageLayout& layout, const std::string& source)
    : layout_(layout)
{
    validate(description, source);
    validate_image_layout(layout, source);
    channel_count_ = layout.channels == "Y" ? 1 : layout.channels == "RGBA" ? 4 : 3;
    const double units_per_pixel = layout.scale / description.pixels_per_unit;
    period_ = {layout.width * units_per_pixel, layout.height * units_per_pixel};
    // Texels lie within one period: bounding it bounds every position a level evaluates.
    check_position(period_[0], description.pixels_per_unit, source + ": image.width × image.scale (the period in u)");
    check_position(period_[1], description.pixels_per_unit, source + ": image.height × image.scale (the period in v)");
    texture_ = make_periodic_texture(description, period_);
    for (int w = layout.width, h = layout.height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        level_sizes_.push_back({w, h});
        if (w == 1 && h == 1) break;
    }
}

void MipImage::fill(int level, int x0, int y0, int w, int h, float* out) const
{
    const int level_w = level_width(level), level_h = level_height(level);
    if (x0 < 0 || y0 < 0 || w < 0 || h < 0 || x0 + w > level_w || y0 + h > level_h)
        throw Error("MIP image: region outside level " + std::to_string(level));
    // A texel of this level spans period / level size: that is its position step and its
    // footprint (levels of odd sizes have slightly non-square texels).
    RasterRegion region;
    region.du = period_[0] / level_w;
    region.dv = period_[1] / level_h;
    region.x0 = x0, region.y0 = y0, region.width = w, region.height = h;
    region.footprint = {region.du, 0, 0, region.dv};
    if (channel_count_ == 3) {
        texture_->eval_region(region, out);
        return;
    }
    std::vector<float> rgb(std::size_t(w) * h * 3);
    texture_->eval_region(region, rgb.data());
    const std::size_t count = std::size_t(w) * h;
    for (std::size_t i = 0; i < count; ++i) {
        const float* texel = &rgb[i * 3];
        if (channel_count_ == 1) {
            out[i] = 0.2126f * texel[0] + 0.7152f * texel[1] + 0.0722f * texel[2];
        } else {
            float* target = out + i * 4;
            target[0] = texel[0], target[1] = texel[1], target[2] = texel[2], target[3] = 1.0f;
        }
    }
}

}  // namespace stochtex
