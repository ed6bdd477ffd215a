// The wavelet model's OSL form (osl/stochtex_wavelet.osl; docs/osl.md): its shader reads the two
// noise tiles, shared by every wavelet texture. Compiled into the OSL front-end, not the core.
#include <stochtex/error.h>
#include <stochtex/models/wavelet_shader_data.h>
#include <stochtex/osl/osl_form.h>

#include <filesystem>

namespace stochtex::osl {

namespace {

// Array sizes of the template's parameters (osl/stochtex_wavelet.h: STOCHTEX_MAX_BANDS).
constexpr int max_bands = 24;
constexpr int atlas_per_row = 8;  // 64 slices of the 3D tile as 8 × 8

std::vector<OslImage> wavelet_images(const std::string& folder, const std::string&)
{
    const std::filesystem::path dir(folder);
    return {{"tile_2d", (dir / "stochtex_noise_2d.exr").string()}, {"tile_3d", (dir / "stochtex_noise_3d.exr").string()}};
}

std::string wavelet_shader(const TextureDescription& description, const OslShaderOptions& options)
{
    const WaveletShaderData data = wavelet_shader_data(description);
    if (data.band_count > max_bands) throw Error("OSL shader: more than 24 bands");
    std::vector<double> weight(3 * max_bands, 0.0), offset(9 * max_bands, 0.0);
    for (int c = 0; c < 3; ++c)
        for (int j = 0; j < data.band_count; ++j) {
            weight[c * max_bands + j] = data.weight[c][j];
            for (int axis = 0; axis < 3; ++axis) offset[(c * max_bands + j) * 3 + axis] = data.offset[c][j][axis];
        }
    const NoiseTile tile_2d = wavelet_noise_tile_2d(), tile_3d = wavelet_noise_tile_3d();
    ParameterBlock block;
    block.add("string tile_2d = " + osl_quoted(options.images.path("tile_2d")));
    block.add("int size_2d = " + std::to_string(tile_2d.width));
    block.add("string tile_3d = " + osl_quoted(options.images.path("tile_3d")));
    block.add("int size_3d = " + std::to_string(tile_3d.width));
    block.add("int per_row_3d = " + std::to_string(atlas_per_row));
    block.add("float pixels_per_unit = " + osl_number(data.pixels_per_unit));
    block.add("int band_count = " + std::to_string(data.band_count));
    block.add("float scale[24] = " + osl_array(data.scale, max_bands));
    block.add("float weight[72] = " + osl_array(weight, weight.size()));
    block.add("float offset[216] = " + osl_array(offset, offset.size()));
    block.add("float sigma_m[3] = " + osl_array({data.sigma_m.begin(), data.sigma_m.end()}, 3));
    block.add("float sigma_n2 = " + osl_number(data.sigma_n2));
    block.add("float solid_gain = " + osl_number(data.solid_gain));
    add_colour(block, data.colour);
    add_joint_colour(block, data.colour.chroma_given_brightness);
    return instantiate_template("stochtex_wavelet.osl", "stochtex_wavelet", block.text, description, options);
}

/// The 2D tile (size² texels) and the 3D tile as an atlas of 8 × 8 slices.
void write_noise_tiles(const TextureDescription&, const OslImagePaths& files)
{
    const NoiseTile tile_2d = wavelet_noise_tile_2d();
    write_float_exr(files.path("tile_2d"), tile_2d.width, tile_2d.height, {"Y"}, tile_2d.coefficients.data(), "noise tile");
    const NoiseTile tile_3d = wavelet_noise_tile_3d();
    const int size = tile_3d.width, atlas = size * atlas_per_row;
    if (tile_3d.depth != atlas_per_row * atlas_per_row) throw Error("3D noise tile: unexpected depth");
    std::vector<float> texels(std::size_t(atlas) * atlas);
    for (int z = 0; z < tile_3d.depth; ++z)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                texels[std::size_t(y + size * (z / atlas_per_row)) * atlas + x + size * (z % atlas_per_row)] =
                    tile_3d.coefficients[(std::size_t(z) * size + y) * size + x];
    write_float_exr(files.path("tile_3d"), atlas, atlas, {"Y"}, texels.data(), "noise tile");
}

const OslFormRegistration registration({"wavelet", wavelet_images, wavelet_shader, write_noise_tiles});

}  // namespace

}  // namespace stochtex::osl
