// The kit the models' OSL forms share (osl_form.h), and the forms' registry.
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/osl/osl_form.h>

#include <cmath>
#include <cstdio>
#include <set>

namespace stochtex::osl {

namespace {

// Array sizes of stochtex_colour.h's parameters (STOCHTEX_MAX_KNOTS, _GH_COUNT, _MAX_JOINT_KNOTS).
constexpr int max_knots = 64, gh_count = 12, max_joint_knots = 64;

std::vector<OslForm>& forms()
{
    static std::vector<OslForm> registered;  // constructed on first use: registrations run before main()
    return registered;
}

std::string replace_once(std::string text, const std::string& from, const std::string& to)
{
    const std::size_t at = text.find(from);
    if (at == std::string::npos) throw Error("OSL shader template: '" + from + "' not found (build is inconsistent)");
    return text.replace(at, from.size(), to);
}

/// Each `#include "file"` line replaced by that file's text, recursively, each file once: the
/// generated shader compiles on its own (Blender's internal scripts have no include path).
std::string inline_includes(const std::string& text, std::set<std::string>& inlined)
{
    std::string out;
    std::size_t at = 0;
    const std::string directive = "#include \"";
    while (at < text.size()) {
        std::size_t end = text.find('\n', at);
        end = end == std::string::npos ? text.size() : end + 1;
        const std::string line = text.substr(at, end - at);
        if (line.compare(0, directive.size(), directive) == 0) {
            const std::string file = line.substr(directive.size(), line.find('"', directive.size()) - directive.size());
            if (inlined.insert(file).second) out += inline_includes(shader_source(file), inlined);
        } else {
            out += line;
        }
        at = end;
    }
    return out;
}

}  // namespace

OslFormRegistration::OslFormRegistration(OslForm form)
{
    if (find_osl_form(form.model)) throw Error("OSL forms: model '" + form.model + "' has two");
    forms().push_back(std::move(form));
}

const OslForm* find_osl_form(const std::string& model)
{
    for (const OslForm& form : forms())
        if (form.model == model) return &form;
    return nullptr;
}

std::string osl_number(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

std::string osl_array(const std::vector<double>& values, std::size_t size)
{
    std::string text = "{ ";
    for (std::size_t i = 0; i < size; ++i) {
        if (i > 0) text += (i % 8 == 0) ? ",\n        " : ", ";
        text += i < values.size() ? osl_number(values[i]) : "0";
    }
    return text + " }";
}

std::string osl_quoted(const std::string& text)
{
    if (text.find_first_of("\"\\\n") != std::string::npos)
        throw Error("OSL shader: the path '" + text + "' contains a quote, backslash or newline");
    return "\"" + text + "\"";
}

void ParameterBlock::add_int_array(const std::string& name, const std::vector<int>& values)
{
    std::string line = "int " + name + "[" + std::to_string(values.size()) + "] = { ";
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i > 0) line += (i % 8 == 0) ? ",\n        " : ", ";
        line += std::to_string(values[i]);
    }
    add(line + " }");
}

/// Knot count, first knot, 1 / knot spacing (computed here in double, as the core's
/// ChromaConditioning does), and the four curves location 1, location 2, scale 1, scale 2, each
/// padded to max_joint_knots.
void add_joint_colour(ParameterBlock& block, const ChromaGivenBrightness& curves)
{
    std::vector<double> values(4 * max_joint_knots, 0.0);
    double first = -3, inverse_step = 8;
    const std::size_t knots = curves.enabled() ? curves.z.size() : 0;
    if (knots > std::size_t(max_joint_knots)) throw Error("OSL shader: more than 64 joint-colour knots");
    if (knots > 0) {
        first = curves.z.front();
        inverse_step = double(knots - 1) / (curves.z.back() - curves.z.front());
        for (int c = 0; c < 2; ++c)
            for (std::size_t k = 0; k < knots; ++k) {
                values[c * max_joint_knots + k] = curves.location[c][k];
                values[(2 + c) * max_joint_knots + k] = curves.scale[c][k];
            }
    }
    block.add("int joint_count = " + std::to_string(knots));
    block.add("float joint_first = " + osl_number(first));
    block.add("float joint_inverse_step = " + osl_number(inverse_step));
    block.add("float joint_curve[256] = " + osl_array(values, values.size()));
}

void add_colour(ParameterBlock& block, const ShaderColourData& colour)
{
    std::vector<double> knot_z(3 * max_knots, 0.0), knot_value(3 * max_knots, 0.0), knot_slope(3 * max_knots, 0.0);
    std::vector<int> knot_count(3, 0);
    std::vector<double> basis;
    for (int c = 0; c < 3; ++c) {
        const auto& curve = colour.histogram[c];
        if (curve.z.size() > std::size_t(max_knots)) throw Error("OSL shader: more than 64 histogram knots");
        knot_count[c] = int(curve.z.size());
        for (std::size_t k = 0; k < curve.z.size(); ++k) {
            knot_z[c * max_knots + k] = curve.z[k];
            knot_value[c * max_knots + k] = curve.value[k];
            knot_slope[c * max_knots + k] = curve.slope[k];
        }
        for (int column = 0; column < 3; ++column) basis.push_back(colour.basis[c][column]);
    }
    std::string counts = "int knot_count[3] = { ";
    for (int c = 0; c < 3; ++c) counts += std::to_string(knot_count[c]) + (c < 2 ? ", " : " }");
    block.add(counts);
    block.add("float knot_z[192] = " + osl_array(knot_z, knot_z.size()));
    block.add("float knot_value[192] = " + osl_array(knot_value, knot_value.size()));
    block.add("float knot_slope[192] = " + osl_array(knot_slope, knot_slope.size()));
    block.add("float gh_node[12] = " + osl_array(colour.gh_node, gh_count));
    block.add("float gh_weight[12] = " + osl_array(colour.gh_weight, gh_count));
    block.add("float mean[3] = " + osl_array({colour.mean.begin(), colour.mean.end()}, 3));
    block.add("float basis[9] = " + osl_array(basis, 9));
}

void append_limbs(std::vector<int>& out, std::uint64_t value)
{
    for (int k = 0; k < 4; ++k) out.push_back(int((value >> (16 * k)) & 0xffff));
}

void split_significant_bits(double value, int bits, double& hi, double& lo)
{
    int exponent = 0;
    std::frexp(value, &exponent);
    hi = std::ldexp(std::round(std::ldexp(value, bits - exponent)), exponent - bits);
    lo = value - hi;
}

std::string instantiate_template(const std::string& file, const std::string& template_name, const std::string& parameters,
                                 const TextureDescription& description, const OslShaderOptions& options)
{
    return instantiate_template_text(shader_source(file), template_name, parameters, description, options);
}

std::string instantiate_template_text(std::string text, const std::string& template_name, const std::string& parameters,
                                      const TextureDescription& description, const OslShaderOptions& options)
{
    const std::string begin = "    // @stochtex-parameters-begin", end = "    // @stochtex-parameters-end\n";
    const std::size_t from = text.find(begin), to = text.find(end);
    if (from == std::string::npos || to == std::string::npos || to < from)
        throw Error("OSL shader template: parameter markers not found (build is inconsistent)");
    // Every shader reads the row probe first (stochtex_subset.h), so the block starts with it.
    const std::string probe = "    string rows_probe = " + osl_quoted(options.images.rows_probe) + ",\n";
    text.replace(from, to + end.size() - from, probe + parameters);
    std::set<std::string> inlined;
    text = inline_includes(text, inlined);
    text = replace_once(text, "shader " + template_name + "(", "shader " + options.shader_name + "(");
    text = replace_once(text, "float Scale = 1.0 [[", "float Scale = " + osl_number(1.0 / description.unit_size_m) + " [[");
    const std::string banner = "// Generated by stochtex " STOCHTEX_VERSION " (stex osl) from " +
                               (options.source_name.empty() ? std::string("a texture") : options.source_name) + ": the " +
                               description.model + " model, seed " + std::to_string(description.seed) +
                               ". Scale defaults to 1 / unit_size_m: coordinates in metres.\n";
    return banner + text;
}

void write_float_exr(const std::string& path, int width, int height, const std::vector<std::string>& channels,
                     const float* values, const char* what)
{
    // A failed write keeps the previous file (write_data_image goes through an AtomicOutput).
    write_data_image(path, width, height, channels, values, std::string("the ") + what);
}

}  // namespace stochtex::osl
