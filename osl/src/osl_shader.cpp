// `stex osl`'s generator: names no model. Each model's form (osl_form.h) lives in its folder,
// core/src/models/<name>/front_ends/<name>_osl.cpp, and is found in the registry.
#include <stochtex/error.h>
#include <stochtex/model.h>
#include <stochtex/osl/osl_form.h>
#include <stochtex/osl/osl_shader.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace stochtex::osl {

namespace {

void validate_shader_name(const std::string& name)
{
    bool ok = !name.empty() && name.size() <= 64 && (std::isalpha((unsigned char)name[0]) || name[0] == '_');
    for (char c : name) ok = ok && (std::isalnum((unsigned char)c) || c == '_');
    if (!ok) throw Error("OSL shader name '" + name + "': expected a letter or '_', then letters, digits or '_' (at most 64)");
}

}  // namespace

const std::string& OslImagePaths::path(const std::string& parameter) const
{
    for (const OslImage& image : images)
        if (image.parameter == parameter) return image.path;
    throw Error("OSL shader: no image '" + parameter + "' among the form's images (build is inconsistent)");
}

std::vector<std::string> OslImagePaths::all() const
{
    std::vector<std::string> paths;
    for (const OslImage& image : images) paths.push_back(image.path);
    if (!rows_probe.empty()) paths.push_back(rows_probe);
    return paths;
}

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

OslImagePaths osl_image_paths(const TextureDescription& description, const std::string& folder, const std::string& shader_stem)
{
    OslImagePaths paths;
    const OslForm* form = find_osl_form(description.model);
    if (!form) return paths;  // no transcription, no images
    paths.images = form->images(folder, shader_stem);
    paths.rows_probe = (std::filesystem::path(folder) / "stochtex_rows.exr").string();
    return paths;
}

std::string make_osl_shader(const TextureDescription& description, const OslShaderOptions& options)
{
    validate_shader_name(options.shader_name);
    if (!has_osl_form(description.model))
        throw Error("model '" + description.model +
                    "' has no OSL transcription: use osl/stochtex_texture.osl with the OIIO plugin, or a baked map");
    const OslForm* form = find_osl_form(description.model);
    if (!form) throw Error("model '" + description.model + "' claims an OSL form that this generator does not know");
    return form->shader(description, options);
}

void write_osl_images(const TextureDescription& description, const OslImagePaths& files)
{
    if (!files.rows_probe.empty()) {
        // 8 x 8 texels, not 1 x 2: an image one texel high or wide is one a host may treat specially.
        constexpr int probe_size = 8;
        std::vector<float> probe(probe_size * probe_size, 0.0f);
        std::fill(probe.begin() + probe.size() / 2, probe.end(), 1.0f);  // the bottom half
        write_float_exr(files.rows_probe, probe_size, probe_size, {"Y"}, probe.data(), "row probe");
    }
    if (const OslForm* form = find_osl_form(description.model)) form->write_images(description, files);
}

}  // namespace stochtex::osl
