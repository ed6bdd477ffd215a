// The model interface and its registry: everything the core does with a model goes through a
// Model found by name, so a model is one folder (models/<name>/) plus one line in registry.cpp
// (docs/architecture.md, "How to add a model"). A model defined outside the core (the test
// suite's) registers itself with a ModelRegistration.
//
// ModelOf<Parameters> does the type-erasure: a model declares its parameter schema once and
// gets the .stex block's read, write and validation from it; it implements only its maths.
#pragma once

#include "schema/parameter_schema.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/model.h>
#include <stochtex/texture.h>

#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

namespace stochtex {

struct ColourBasis;

// ---- Analysis options declared by a model ------------------------------------------------------

/// One `stex analyze` option of a model: its declaration and how its text is checked.
/// `canonical` returns the text the fit reads (the user's, or a normal form such as "auto") or
/// throws Error with the problem.
struct AnalysisOption {
    ParameterInfo info;
    std::function<std::string(const std::string& text)> canonical;
};

/// What analysis hands a model's fit: the photo's decorrelated channels (Gaussianised where a
/// histogram map was kept), the colour basis and the band count the photo supports.
struct FitInput {
    const std::array<std::vector<float>, 3>& channels;
    int width = 0, height = 0;
    const ColourBasis& colour;
    const std::array<HistogramMap, 3>& histograms;  ///< kept maps (the channel was Gaussianised)
    int band_count = 0;  ///< min(AnalysisOptions::max_bands, what the photo supports)
    const AnalysisOptions& options;
    /// The model's own analysis options from options.model_options, checked against their
    /// declarations (absent ones: the declared default): name → the text as given.
    std::map<std::string, std::string> model_options;
    /// Scores parameters the fit considers as `--model auto` scores a model
    /// (analysis/model_choice.h: score_against_photo): the description being fitted, with these
    /// parameters, rendered at most max_side² and compared with the photo. For a fit that
    /// chooses among candidates of its own by what their renders look like (tiling's automatic
    /// exemplar size).
    std::function<ModelScore(const ModelParameters& parameters, int max_side)> score;
    /// Which of such scores to keep, by `--model auto`'s rule (analysis/model_choice.h:
    /// chosen_by_rule): the index of the lowest penalty or, among those within
    /// model_choice_tolerance of it, the smallest file. Given to the fit, not included by it, so
    /// a fit keeps its candidates as the choice keeps models while the models stay below
    /// analysis/ (docs/architecture.md, "Layers").
    std::function<std::size_t(const std::vector<ModelScore>& scores)> choose;
};

/// A fit changed in options that need no refit (Model::automatic_variants).
struct FitVariant {
    /// The provenance options the change sets, "name value" joined by ", " (ModelScore::variant).
    std::string label;
    TextureDescription description;
};

class Model {
public:
    virtual ~Model() = default;
    Model(const Model&) = delete;
    Model& operator=(const Model&) = delete;

    const ModelInfo& info() const { return info_; }
    const std::string& name() const { return info_.name; }

    // ---- The .stex "parameters" block (ModelOf implements these from the schema) --------------
    /// Whether `parameters` holds this model's struct.
    virtual bool holds(const ModelParameters& parameters) const = 0;
    /// Reads the block; `stex_path` locates files kept beside the .stex.
    virtual ModelParameters read_parameters(const json_fields::Field& block, const std::string& stex_path) const = 0;
    virtual json_fields::Json write_parameters(const TextureDescription& description) const = 0;
    /// Checks the parameters (and what the model requires of the shared fields, e.g. colour).
    virtual void validate(const TextureDescription& description, const std::string& source) const = 0;
    /// Before a description is written to `stex_path`: writes what the model keeps beside it
    /// and returns the description naming those files. Most models keep nothing there.
    virtual TextureDescription write_beside(const std::string& stex_path, const TextureDescription& description) const
    {
        (void)stex_path;
        return description;
    }

    // ---- Textures ----------------------------------------------------------------------------
    virtual std::unique_ptr<Texture> make_texture(const TextureDescription& description) const = 0;
    virtual std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& description,
                                                           const Vec2& period) const = 0;
    /// The model's lines of `stex info` (after the shared colour and histogram lines).
    virtual std::string describe(const TextureDescription& description) const = 0;

    /// A small valid description of this model, for the conformance suite (tests/) that every
    /// registered model passes. The default analyses a synthetic photo (capabilities.analysis).
    virtual TextureDescription example() const;

    // ---- Capabilities (info().capabilities says which are there; the others throw) -----------
    /// Fits the model's parameters from a photo (capabilities.analysis) and appends its options
    /// to the provenance.
    virtual ModelParameters fit(const FitInput& input, Provenance& provenance) const;
    /// The parameters between a (t = 0) and b (t = 1); b's colour axes are already aligned with
    /// a's (capabilities.morph).
    virtual ModelParameters morph(const TextureDescription& a, const TextureDescription& b, double t) const;
    /// σ_M of decorrelated channel c (capabilities.gaussian_channels).
    virtual double channel_sigma(const TextureDescription& description, int channel) const;
    /// The light direction (capabilities.light_direction).
    virtual Vec3 light(const TextureDescription& description) const;
    virtual void set_light(TextureDescription& description, const Vec3& unit_direction) const;

    /// Variants of a fit that `--model auto` scores beside it where it scores structure
    /// (AnalysisOptions::structure_in_choice): copies of `fitted` with an option changed that needs
    /// no refit, each naming the provenance options it sets ("blend_contrast 8"). Options the
    /// caller gave (`given`, their keys) are not varied. Most models offer none.
    virtual std::vector<FitVariant> automatic_variants(const TextureDescription& fitted,
                                                       const std::set<std::string>& given) const
    {
        (void)fitted, (void)given;
        return {};
    }

    /// Option sets (declared options, name → text) `--model auto` fits the model with again,
    /// beside its own fit, where it scores structure: choices that need a refit (tiling's larger
    /// exemplar) for a width × height photo. Each refit's variants are tried too. Options the caller
    /// gave (`given`) are not varied. Most models offer none.
    virtual std::vector<std::vector<std::pair<std::string, std::string>>> automatic_refits(
        int width, int height, const std::set<std::string>& given) const
    {
        (void)width, (void)height, (void)given;
        return {};
    }

    /// The model's `stex analyze` options (capabilities.analysis), as declared.
    const std::vector<AnalysisOption>& analysis_options() const { return analysis_options_; }

protected:
    explicit Model(ModelInfo info) : info_(std::move(info)) {}
    /// Declares the analysis options (once, in the model's constructor).
    void declare_analysis_options(std::vector<AnalysisOption> options);
    [[noreturn]] void unsupported(const std::string& what) const;

private:
    ModelInfo info_;
    std::vector<AnalysisOption> analysis_options_;
};

/// A model whose parameters are the struct `Parameters`, declared by `schema`.
template <class Parameters>
class ModelOf : public Model {
public:
    bool holds(const ModelParameters& parameters) const final { return parameters.holds<Parameters>(); }
    ModelParameters read_parameters(const json_fields::Field& block, const std::string& stex_path) const override
    {
        return schema_.read(block, {stex_path});
    }
    json_fields::Json write_parameters(const TextureDescription& description) const override
    {
        return schema_.write(parameters(description));
    }
    void validate(const TextureDescription& description, const std::string& source) const override
    {
        schema_.validate(parameters(description), "parameters", source);
    }

    static const Parameters& parameters(const TextureDescription& description)
    {
        return description.parameters.get<Parameters>();
    }
    const ParameterSchema<Parameters>& schema() const { return schema_; }

protected:
    /// `info.parameters` is filled from the schema.
    ModelOf(ModelInfo info, ParameterSchema<Parameters> schema) : Model(with_parameters(std::move(info), schema)), schema_(std::move(schema)) {}

private:
    static ModelInfo with_parameters(ModelInfo info, const ParameterSchema<Parameters>& schema)
    {
        info.parameters = schema.infos();
        return info;
    }
    ParameterSchema<Parameters> schema_;
};

/// A ModelOf whose texture is `TextureType`, made from (description) and, for the periodic
/// form, (description, period).
template <class Parameters, class TextureType>
class TextureModelOf : public ModelOf<Parameters> {
public:
    std::unique_ptr<Texture> make_texture(const TextureDescription& description) const override
    {
        return std::make_unique<TextureType>(description);
    }
    std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& description, const Vec2& period) const override
    {
        return std::make_unique<TextureType>(description, period);
    }

protected:
    using ModelOf<Parameters>::ModelOf;
};

// ---- The registry -------------------------------------------------------------------------------

/// Every registered model, in registration order (built-in models first: registry.cpp).
const std::vector<const Model*>& registered_models();
/// The named model, or null.
const Model* find_model(const std::string& name);
/// The named model; otherwise fails with "<source>: <path>: unknown model 'x' (known models: …)".
// The error context is taken as string_view: a reference-returning function given temporary
// std::strings looks to g++ 13+ like it might return one of them (-Wdangling-reference), and the
// context is only read on failure.
const Model& model_named(const std::string& name, std::string_view source, std::string_view path = "model");
/// The model of a description (model_named(description.model, source)).
inline const Model& model_of(const TextureDescription& description, std::string_view source = "texture description")
{
    return model_named(description.model, source);
}

/// Registers a model defined outside the core's folders (a static object of this type in the
/// model's file): `model` must outlive the process' use of the registry.
struct ModelRegistration {
    explicit ModelRegistration(const Model& model);
};

/// A number option in [min, max] (or the word `word`, when given, e.g. "auto").
AnalysisOption number_option(const char* key, double min, double max, FieldDoc doc, std::string word = "",
                             bool max_open = false);
/// An integer option in [min, max] (or the word `word`, when given, e.g. "auto").
AnalysisOption integer_option(const char* key, long min, long max, FieldDoc doc, std::string word = "");
/// One of `choices`.
AnalysisOption choice_option(const char* key, std::vector<std::string> choices, FieldDoc doc);

/// How an option's value is recorded in the provenance: numbers as ostream prints them (as
/// analysis recorded them before options were declared), words as they are.
std::string recorded_option(const std::map<std::string, std::string>& options, const std::string& key);
/// The ParameterInfos of `options`, for ModelInfo::analysis_options.
std::vector<ParameterInfo> option_infos(const std::vector<AnalysisOption>& options);
/// `model`'s options from `given` (name → text; unknown names are errors naming the model), each
/// checked and canonical; absent ones take their declared default.
std::map<std::string, std::string> parse_model_options(const Model& model,
                                                      const std::vector<std::pair<std::string, std::string>>& given);

}  // namespace stochtex
