// stochtex — the registered models: what each is, what it can do and what it declares.
//
// Every list of models (the .stex reader, `stex analyze --model`, `stex --list-models`, the
// Blender add-on, the docs) comes from the registry, and every front-end decides what to offer
// from a model's capabilities, never from its name. The registry itself (how a model plugs in)
// is private to the core: core/src/models/model.h, and docs/architecture.md.
#pragma once

#include <string>
#include <vector>

namespace stochtex {

/// What a model can do beyond the 2D filtered evaluation every model has.
struct ModelCapabilities {
    bool analysis = false;           ///< `stex analyze --model NAME` fits it from one photo
    bool solid = false;              ///< eval_solid() is a true solid texture (not a projection)
    bool morph = false;              ///< morph() interpolates two textures of the model
    bool pov_procedural = false;     ///< `stex pov --mode procedural` can write it as POV-Ray SDL
    bool osl = false;                ///< `stex osl` can write it as an OSL shader
    bool light_direction = false;    ///< evaluated for a light direction (stochtex/lighting.h)
    bool gaussian_channels = false;  ///< Gaussian decorrelated channels with a σ_M (channel_map.h)
    /// Analysis can tie the chroma channels to brightness (`--joint-colour`): the synthesis maps
    /// decorrelated channels through the shared colour stage (TextureDescription::chroma_given_brightness).
    bool joint_colour = false;
};

/// One declared parameter: of a model's .stex "parameters" block, or an analysis option.
struct ParameterInfo {
    std::string key;            ///< JSON key, or the option's name (`--key` on the command line)
    std::string type;           ///< "number", "integer", "boolean", "string", "numbers", "object", …
    std::string range;          ///< allowed values: "[0.0625, 16]", "isotropic | anisotropic", …
    std::string default_value;  ///< what analysis or a new description uses; "" when none applies
    std::string unit;           ///< "exemplar px", "cycles / exemplar px", …; "" when unitless
    std::string doc;            ///< one line
    std::vector<ParameterInfo> fields;  ///< members of an object, or of each element of a list
    bool optional = false;      ///< the key may be absent
};

/// A registered model, as front-ends and documentation see it.
struct ModelInfo {
    std::string name;     ///< the "model" of a .stex file
    std::string summary;  ///< one line: what the model is for
    std::string doc;      ///< its page, e.g. "docs/models/wavelet.md"
    ModelCapabilities capabilities;
    std::vector<ParameterInfo> parameters;        ///< the .stex "parameters" block
    std::vector<ParameterInfo> analysis_options;  ///< `stex analyze` options of this model
    /// The colour modes (`--colour` values) `analyze --model auto` fits this model with when no
    /// colour mode is given: pca, the analysis's default, for every model; a model whose
    /// synthesis treats all channels alike (tiling blends them with the same weights) adds rgb,
    /// which keeps chroma extremes that never co-occur in the photo from meeting.
    std::vector<std::string> automatic_colour_modes{"pca"};
};

/// Model names, in registration order (the built-in models first).
const std::vector<std::string>& known_models();
/// The named model's information; throws Error listing the known models if there is none.
const ModelInfo& model_info(const std::string& name);
/// Every registered model's information, in registration order.
std::vector<const ModelInfo*> registered_model_infos();

/// The registry as JSON (name, summary, doc, capabilities, parameters, analysis options), for
/// programs that run `stex --list-models --json` (the Blender add-on) and for the docs' tables.
std::string models_json();
/// The Markdown table of one model's parameters (docs/stex-format.md holds one per model, and a
/// test checks it against this).
std::string parameter_table_markdown(const ModelInfo& model);
/// The same table for any declared fields, keys as JSON paths below `parent` ("image" → `image.width`).
std::string parameter_table_markdown(const std::vector<ParameterInfo>& fields, const std::string& parent);

}  // namespace stochtex
