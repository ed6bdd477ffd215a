// The OSL form of the test suite's model with every capability (test_everything_model.cpp): a
// shader of its own template, its texture's mean colour as a constant block. Small on purpose:
// it shows that a form registers itself and `stex osl` finds it, not how to transcribe noise.
#include <stochtex/osl/osl_form.h>

namespace stochtex::osl {

namespace {

const char* const test_everything_template = R"osl(// The test_everything model: its mean colour.
shader stochtex_test_everything(
    // @stochtex-parameters-begin
    // @stochtex-parameters-end
    float Scale = 1.0 [[ string help = "texture units per scene unit (unused: a constant)" ]],
    output color Cout = 0)
{
    Cout = color(mean[0], mean[1], mean[2]);
}
)osl";

std::string test_everything_shader(const TextureDescription& description, const OslShaderOptions& options)
{
    ParameterBlock block;
    block.add("float mean[3] = " + osl_array({description.mean.begin(), description.mean.end()}, 3));
    return instantiate_template_text(test_everything_template, "stochtex_test_everything", block.text, description, options);
}

const OslFormRegistration registration({"test_everything",
                                        [](const std::string&, const std::string&) { return std::vector<OslImage>{}; },
                                        test_everything_shader, [](const TextureDescription&, const OslImagePaths&) {}});

}  // namespace

}  // namespace stochtex::osl
