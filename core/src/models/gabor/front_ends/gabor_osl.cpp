// The gabor model's OSL form (osl/stochtex_gabor.osl; docs/osl.md): its shader reads the
// sphere-average table, shared by every gabor texture. Compiled into the OSL front-end, not the core.
#include <stochtex/error.h>
#include <stochtex/models/gabor_shader_data.h>
#include <stochtex/osl/osl_form.h>

#include <filesystem>

namespace stochtex::osl {

namespace {

// Array sizes of the template's parameters (osl/stochtex_gabor.h: STOCHTEX_GABOR_MAX_OCTAVES, _STRIDE).
constexpr int max_octaves = 24, octave_stride = 16;

std::vector<OslImage> gabor_images(const std::string& folder, const std::string&)
{
    return {{"sphere_table", (std::filesystem::path(folder) / "stochtex_gabor_sphere.exr").string()}};
}

/// The octaves' fields, octave_stride a row, and their keys as 16-bit limbs, each padded to max_octaves.
void add_octaves(ParameterBlock& block, const GaborShaderData& data)
{
    std::vector<double> octave(std::size_t(max_octaves) * octave_stride, 0.0);
    std::vector<int> key_2d, key_3d, oriented_below;
    for (std::size_t k = 0; k < data.octaves.size(); ++k) {
        const GaborShaderOctave& o = data.octaves[k];
        double cell_2d_hi = 0, cell_2d_lo = 0, cell_3d_hi = 0, cell_3d_lo = 0;
        split_significant_bits(o.cell_2d, 8, cell_2d_hi, cell_2d_lo);
        split_significant_bits(o.cell_3d, 8, cell_3d_hi, cell_3d_lo);
        const double fields[octave_stride] = {o.frequency,          o.bandwidth,          o.radius,
                                              cell_2d_hi,           cell_2d_lo,           cell_3d_hi,
                                              cell_3d_lo,           o.gain_2d,            o.gain_3d,
                                              o.weight[0],          o.weight[1],          o.weight[2],
                                              o.oriented_fraction,  o.orientation[0],     o.orientation[1],
                                              o.orientation[2]};
        for (int f = 0; f < octave_stride; ++f) octave[k * octave_stride + f] = fields[f];
        append_limbs(key_2d, o.key_2d);
        append_limbs(key_3d, o.key_3d);
        append_limbs(oriented_below, o.oriented_below);
    }
    key_2d.resize(4 * max_octaves, 0);
    key_3d.resize(4 * max_octaves, 0);
    oriented_below.resize(4 * max_octaves, 0);
    block.add("int octave_count = " + std::to_string(data.octaves.size()));
    block.add("float octave[384] = " + osl_array(octave, octave.size()));
    block.add_int_array("key_2d", key_2d);
    block.add_int_array("key_3d", key_3d);
    block.add_int_array("oriented_below", oriented_below);
}

std::string gabor_shader(const TextureDescription& description, const OslShaderOptions& options)
{
    const GaborShaderData data = gabor_shader_data(description);
    if (data.octaves.size() > std::size_t(max_octaves)) throw Error("OSL shader: more than 24 octaves");
    const GaborSphereTable table = gabor_sphere_table();
    ParameterBlock block;
    block.add("string sphere_table = " + osl_quoted(options.images.path("sphere_table")));
    block.add("int sphere_table_size = " + std::to_string(table.size));
    block.add("float sphere_table_step = " + osl_number(table.step));
    block.add("float pixels_per_unit = " + osl_number(data.pixels_per_unit));
    add_octaves(block, data);
    block.add("int kind = " + std::to_string(data.kind));
    block.add("float direction[3] = " + osl_array({data.direction.begin(), data.direction.end()}, 3));
    block.add("float direction_length = " + osl_number(data.direction_length));
    block.add("float plane_e1[3] = " + osl_array({data.plane_e1.begin(), data.plane_e1.end()}, 3));
    block.add("float plane_e2[3] = " + osl_array({data.plane_e2.begin(), data.plane_e2.end()}, 3));
    block.add("int channels = " + std::to_string(data.channels));
    block.add("float sigma_m[3] = " + osl_array({data.sigma_m.begin(), data.sigma_m.end()}, 3));
    add_colour(block, data.colour);
    add_joint_colour(block, data.colour.chroma_given_brightness);
    return instantiate_template("stochtex_gabor.osl", "stochtex_gabor", block.text, description, options);
}

void write_sphere_table(const TextureDescription&, const OslImagePaths& files)
{
    const GaborSphereTable table = gabor_sphere_table();
    write_float_exr(files.path("sphere_table"), table.size, table.size, {"Y"}, table.values.data(), "sphere-average table");
}

const OslFormRegistration registration({"gabor", gabor_images, gabor_shader, write_sphere_table});

}  // namespace

}  // namespace stochtex::osl
