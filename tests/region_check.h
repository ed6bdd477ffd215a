// A check every model with a fast raster path shares: Texture::eval_region must return exactly
// eval()'s values (tiles of the plugin, renders and single lookups agree bit for bit).
#pragma once

#include <stochtex/texture.h>

#include <gtest/gtest.h>

#include <vector>

namespace stochtex::test {

/// A 23×11 region at an odd origin, pixel steps and offsets, at footprints of 0, 1, 3 and 40
/// exemplar pixels: every value equal to eval() at the same point and footprint.
inline void expect_region_matches_points(const Texture& texture, double pixels_per_unit)
{
    for (double footprint_px : {0.0, 1.0, 3.0, 40.0}) {
        RasterRegion region;
        region.origin_u = -0.3, region.origin_v = 0.7;
        region.du = 1.3 / pixels_per_unit, region.dv = 0.9 / pixels_per_unit;
        region.x0 = 17, region.y0 = -5, region.width = 23, region.height = 11;
        region.footprint = Footprint2D::square(footprint_px / pixels_per_unit);
        std::vector<float> rgb(std::size_t(region.width) * region.height * 3);
        texture.eval_region(region, rgb.data());
        for (int y = 0; y < region.height; ++y)
            for (int x = 0; x < region.width; ++x) {
                const Rgb expected = texture.eval({region.u(x), region.v(y)}, region.footprint);
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(rgb[(std::size_t(y) * region.width + x) * 3 + std::size_t(c)], expected[std::size_t(c)])
                        << "pixel " << x << ", " << y << ", footprint " << footprint_px;
            }
    }
}

}  // namespace stochtex::test
