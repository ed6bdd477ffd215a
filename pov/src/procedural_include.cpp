// Procedural mode: the texture as SDL that POV-Ray evaluates itself (docs/pov.md). Each model's
// form lives in its folder (core/src/models/<name>/front_ends/<name>_pov.cpp) and registers
// itself; this file only finds it.
#include "include_modes.h"

#include <stochtex/error.h>
#include <stochtex/pov/pov_procedural_form.h>

#include <vector>

namespace stochtex::pov {

namespace {

std::vector<PovProceduralForm>& forms()
{
    static std::vector<PovProceduralForm> registered;  // constructed on first use: registrations run before main()
    return registered;
}

}  // namespace

PovProceduralFormRegistration::PovProceduralFormRegistration(PovProceduralForm form)
{
    if (find_pov_procedural_form(form.model))
        throw Error("POV-Ray procedural forms: model '" + form.model + "' has two");
    forms().push_back(std::move(form));
}

const PovProceduralForm* find_pov_procedural_form(const std::string& model)
{
    for (const PovProceduralForm& form : forms())
        if (form.model == model) return &form;
    return nullptr;
}

PovInclude make_procedural_include(const TextureDescription& description, const PovIncludeOptions& options)
{
    const PovProceduralForm* form = find_pov_procedural_form(description.model);
    if (!form)
        throw Error("model '" + description.model + "' claims a procedural POV-Ray form that this generator does not know");
    return form->include(description, options);
}

}  // namespace stochtex::pov
