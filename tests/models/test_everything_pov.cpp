// The procedural POV-Ray form of the test suite's model with every capability
// (test_everything_model.cpp): its texture's mean colour as SDL. Small on purpose: it shows that
// a form registers itself and `stex pov --mode procedural` finds it.
#include <stochtex/pov/pov_procedural_form.h>
#include <stochtex/pov/sdl_text.h>

namespace stochtex::pov {

namespace {

PovInclude test_everything_include(const TextureDescription& description, const PovIncludeOptions& options)
{
    const std::string& n = options.name;
    const std::string documentation = include_preamble(description, options) + "\nThe test_everything model: its mean colour.\n";
    PovInclude include;
    include.text = sdl_include_begin(n, documentation) + "#declare " + n + "_Mean = rgb " +
                   sdl_vector({description.mean[0], description.mean[1], description.mean[2]}) + ";\n" +
                   "#declare " + n + "_Pigment = pigment { " + n + "_Mean }\n" + "#declare " + n + " = texture { pigment { " +
                   n + "_Pigment } }\n" + sdl_include_end(n);
    include.summary = "procedural: the test_everything model's mean colour";
    return include;
}

const PovProceduralFormRegistration registration({"test_everything", test_everything_include});

}  // namespace

}  // namespace stochtex::pov
