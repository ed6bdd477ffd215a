// The tiling model's OSL form (osl/stochtex_tiling.osl; docs/osl.md): its shader reads the
// exemplar's moment pyramid, one per texture. Compiled into the OSL front-end, not the core.
#include <stochtex/models/tiling_shader_data.h>
#include <stochtex/osl/osl_form.h>

#include <cmath>
#include <filesystem>

namespace stochtex::osl {

namespace {

constexpr int moment_channels = 9, moment_grid = 3;  // osl/stochtex_tiling.h: STOCHTEX_TILING_MOMENTS, _GRID

std::vector<OslImage> tiling_images(const std::string& folder, const std::string& shader_stem)
{
    return {{"moments", (std::filesystem::path(folder) / (shader_stem + "_moments.exr")).string()}};
}

std::string tiling_shader(const TextureDescription& description, const OslShaderOptions& options)
{
    const TilingShaderData data = tiling_shader_data(description);
    double x_hi = 0, x_lo = 0, y_hi = 0, y_lo = 0;
    split_significant_bits(data.edge_x, 12, x_hi, x_lo);
    split_significant_bits(data.edge_y * (0.5 * std::sqrt(3.0)), 12, y_hi, y_lo);
    std::vector<int> seed;
    append_limbs(seed, data.seed);
    ParameterBlock block;
    block.add("string moments = " + osl_quoted(options.images.path("moments")));
    block.add("int width = " + std::to_string(data.width));
    block.add("int height = " + std::to_string(data.height));
    block.add("int atlas_height = " + std::to_string(data.atlas_height));
    block.add("int level_count = " + std::to_string(data.level_count));
    block.add("float pixels_per_unit = " + osl_number(data.pixels_per_unit));
    block.add("int output_kind = " + std::to_string(data.output));
    block.add("int taps = " + std::to_string(data.taps));
    block.add("int max_taps = " + std::to_string(data.max_taps));
    block.add_int_array("seed", seed);
    block.add("float edge_x = " + osl_number(data.edge_x));
    block.add("float edge_y = " + osl_number(data.edge_y));
    block.add("float centre_x_hi = " + osl_number(x_hi));
    block.add("float centre_x_lo = " + osl_number(x_lo));
    block.add("float centre_y_hi = " + osl_number(y_hi));
    block.add("float centre_y_lo = " + osl_number(y_lo));
    block.add("float global_mean[3] = " + osl_array({data.global_mean.begin(), data.global_mean.end()}, 3));
    add_colour(block, data.colour);
    return instantiate_template("stochtex_tiling.osl", "stochtex_tiling", block.text, description, options);
}

/// The 9 moment planes as a 3 x 3 grid of one channel (stochtex_tiling_texel says why).
void write_moment_atlas(const TextureDescription& description, const OslImagePaths& files)
{
    const TilingShaderData data = tiling_shader_data(description);
    const int w = data.width, h = data.atlas_height, grid_w = moment_grid * w;
    std::vector<float> planes(std::size_t(moment_channels) * w * h);
    for (int k = 0; k < moment_channels; ++k)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                planes[std::size_t(y + h * (k / moment_grid)) * grid_w + x + w * (k % moment_grid)] =
                    data.atlas[(std::size_t(y) * w + x) * moment_channels + k];
    write_float_exr(files.path("moments"), grid_w, moment_grid * h, {"Y"}, planes.data(), "moment pyramid");
}

const OslFormRegistration registration({"tiling", tiling_images, tiling_shader, write_moment_atlas});

}  // namespace

}  // namespace stochtex::osl
