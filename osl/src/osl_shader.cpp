#include <stochtex/atomic_write.h>
#include <stochtex/error.h>
#include <stochtex/model.h>
#include <stochtex/osl/osl_shader.h>
#include <stochtex/models/wavelet_shader_data.h>

#include <OpenImageIO/imageio.h>

#include <cctype>
#include <cstdio>
#include <filesystem>

namespace stochtex::osl {

namespace {

// Array sizes of osl/stochtex_wavelet.osl's parameters (STOCHTEX_MAX_BANDS, _KNOTS, _GH_COUNT).
constexpr int max_bands = 24, max_knots = 64, gh_count = 12;
constexpr int atlas_per_row = 8;  // 64 slices of the 3D tile as 8 × 8

std::string number(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

/// "{ a, b, … }" padded with zeros to `size` entries, wrapped for reading.
std::string array(const std::vector<double>& values, std::size_t size)
{
    std::string text = "{ ";
    for (std::size_t i = 0; i < size; ++i) {
        if (i > 0) text += (i % 8 == 0) ? ",\n        " : ", ";
        text += i < values.size() ? number(values[i]) : "0";
    }
    return text + " }";
}

std::string quoted(const std::string& text)
{
    if (text.find_first_of("\"\\\n") != std::string::npos)
        throw Error("OSL shader: the path '" + text + "' contains a quote, backslash or newline");
    return "\"" + text + "\"";
}

void validate_shader_name(const std::string& name)
{
    bool ok = !name.empty() && name.size() <= 64 && (std::isalpha((unsigned char)name[0]) || name[0] == '_');
    for (char c : name) ok = ok && (std::isalnum((unsigned char)c) || c == '_');
    if (!ok) throw Error("OSL shader name '" + name + "': expected a letter or '_', then letters, digits or '_' (at most 64)");
}

std::string replace_once(std::string text, const std::string& from, const std::string& to)
{
    const std::size_t at = text.find(from);
    if (at == std::string::npos) throw Error("OSL shader template: '" + from + "' not found (build is inconsistent)");
    return text.replace(at, from.size(), to);
}

void write_single_channel_exr(const std::string& path, int width, int height, const float* values)
{
    auto output = OIIO::ImageOutput::create(path);
    if (!output) throw Error(path + ": cannot write: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"Y"};
    spec.attribute("compression", "zip");
    spec.attribute("oiio:ColorSpace", "Linear");  // data, not colour: no conversion anywhere
    spec.attribute("Software", "stochtex " STOCHTEX_VERSION);
    AtomicOutput file(path);  // a failed write keeps the previous tile
    if (!output->open(file.temporary(), spec) || !output->write_image(OIIO::TypeDesc::FLOAT, values) || !output->close())
        throw Error(path + ": cannot write the noise tile: " + output->geterror());
    file.commit();
}

}  // namespace

bool has_osl_form(const std::string& model)
{
    for (const ModelInfo* info : registered_model_infos())
        if (info->name == model) return info->capabilities.osl;
    return false;
}

std::string osl_shader_name_from_path(const std::string& path)
{
    std::string name = "stochtex_";
    for (char c : std::filesystem::path(path).stem().string()) name += std::isalnum((unsigned char)c) ? c : '_';
    return name.substr(0, 64);
}

std::string make_osl_shader(const TextureDescription& description, const OslShaderOptions& options)
{
    validate_shader_name(options.shader_name);
    if (!has_osl_form(description.model))
        throw Error("model '" + description.model +
                    "' has no OSL transcription: use osl/stochtex_texture.osl with the OIIO plugin, or a baked map");
    const WaveletShaderData data = wavelet_shader_data(description);
    if (data.band_count > max_bands) throw Error("OSL shader: more than 24 bands");

    std::vector<double> weight(3 * max_bands, 0.0), offset(9 * max_bands, 0.0);
    std::vector<double> knot_z(3 * max_knots, 0.0), knot_value(3 * max_knots, 0.0), knot_slope(3 * max_knots, 0.0);
    std::vector<double> knot_count(3, 0.0), basis;
    for (int c = 0; c < 3; ++c) {
        for (int j = 0; j < data.band_count; ++j) {
            weight[c * max_bands + j] = data.weight[c][j];
            for (int axis = 0; axis < 3; ++axis) offset[(c * max_bands + j) * 3 + axis] = data.offset[c][j][axis];
        }
        const auto& curve = data.histogram[c];
        if (curve.z.size() > std::size_t(max_knots)) throw Error("OSL shader: more than 64 histogram knots");
        knot_count[c] = double(curve.z.size());
        for (std::size_t k = 0; k < curve.z.size(); ++k) {
            knot_z[c * max_knots + k] = curve.z[k];
            knot_value[c * max_knots + k] = curve.value[k];
            knot_slope[c * max_knots + k] = curve.slope[k];
        }
        for (int column = 0; column < 3; ++column) basis.push_back(data.basis[c][column]);
    }
    const NoiseTile tile_2d = wavelet_noise_tile_2d(), tile_3d = wavelet_noise_tile_3d();

    std::string parameters;
    auto add = [&](const std::string& declaration) { parameters += "    " + declaration + ",\n"; };
    add("string tile_2d = " + quoted(options.tile_2d_path));
    add("int size_2d = " + std::to_string(tile_2d.width));
    add("string tile_3d = " + quoted(options.tile_3d_path));
    add("int size_3d = " + std::to_string(tile_3d.width));
    add("int per_row_3d = " + std::to_string(atlas_per_row));
    add("float pixels_per_unit = " + number(data.pixels_per_unit));
    add("int band_count = " + std::to_string(data.band_count));
    add("float scale[24] = " + array(data.scale, max_bands));
    add("float weight[72] = " + array(weight, weight.size()));
    add("float offset[216] = " + array(offset, offset.size()));
    add("float sigma_m[3] = " + array({data.sigma_m.begin(), data.sigma_m.end()}, 3));
    add("float sigma_n2 = " + number(data.sigma_n2));
    add("float solid_gain = " + number(data.solid_gain));
    std::string counts = "int knot_count[3] = { ";
    for (int c = 0; c < 3; ++c) counts += std::to_string(int(knot_count[c])) + (c < 2 ? ", " : " }");
    add(counts);
    add("float knot_z[192] = " + array(knot_z, knot_z.size()));
    add("float knot_value[192] = " + array(knot_value, knot_value.size()));
    add("float knot_slope[192] = " + array(knot_slope, knot_slope.size()));
    add("float gh_node[12] = " + array(data.gh_node, gh_count));
    add("float gh_weight[12] = " + array(data.gh_weight, gh_count));
    add("float mean[3] = " + array({data.mean.begin(), data.mean.end()}, 3));
    add("float basis[9] = " + array(basis, 9));

    // The template's parameter block (between the markers) becomes the texture's numbers; the
    // header is inlined so that the file compiles on its own (Blender's internal scripts).
    std::string text = wavelet_shader_source();
    const std::string begin = "    // @stochtex-parameters-begin", end = "    // @stochtex-parameters-end\n";
    const std::size_t from = text.find(begin), to = text.find(end);
    if (from == std::string::npos || to == std::string::npos || to < from)
        throw Error("OSL shader template: parameter markers not found (build is inconsistent)");
    text.replace(from, to + end.size() - from, parameters);
    text = replace_once(text, "#include \"stochtex_wavelet.h\"\n", wavelet_header_source());
    text = replace_once(text, "shader stochtex_wavelet(", "shader " + options.shader_name + "(");
    // Scale: coordinates in metres (object space, P) to texture units.
    text = replace_once(text, "float Scale = 1.0 [[", "float Scale = " + number(1.0 / description.unit_size_m) + " [[");
    const std::string banner = "// Generated by stochtex " STOCHTEX_VERSION " (stex osl) from " +
                               (options.source_name.empty() ? std::string("a texture") : options.source_name) +
                               ": the wavelet model, seed " + std::to_string(description.seed) +
                               ". Scale defaults to 1 / unit_size_m: coordinates in metres.\n";
    return banner + text;
}

void write_noise_tiles(const std::string& path_2d, const std::string& path_3d)
{
    const NoiseTile tile_2d = wavelet_noise_tile_2d();
    write_single_channel_exr(path_2d, tile_2d.width, tile_2d.height, tile_2d.coefficients.data());
    const NoiseTile tile_3d = wavelet_noise_tile_3d();
    const int size = tile_3d.width, atlas = size * atlas_per_row;
    if (tile_3d.depth != atlas_per_row * atlas_per_row) throw Error("3D noise tile: unexpected depth");
    std::vector<float> texels(std::size_t(atlas) * atlas);
    for (int z = 0; z < tile_3d.depth; ++z)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                texels[std::size_t(y + size * (z / atlas_per_row)) * atlas + x + size * (z % atlas_per_row)] =
                    tile_3d.coefficients[(std::size_t(z) * size + y) * size + x];
    write_single_channel_exr(path_3d, atlas, atlas, texels.data());
}

}  // namespace stochtex::osl
