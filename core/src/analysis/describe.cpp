#include <stochtex/describe.h>
#include <stochtex/texture.h>

#include "models/info_text.h"
#include "models/model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace stochtex {

std::string describe(const TextureDescription& d)
{
    std::ostringstream out;
    out << "model        " << d.model << " (format version " << d.version << ")\n";
    out << "seed         " << d.seed << "\n";
    out << "scale        " << d.pixels_per_unit << " exemplar pixels per texture unit; unit = " << d.unit_size_m
        << " m\n";
    if (!d.provenance.source.empty())
        out << "source       " << d.provenance.source << " (" << d.provenance.source_width << "x"
            << d.provenance.source_height << ", " << d.provenance.input_colour_space << ")\n";
    if (!d.provenance.model_choice.empty()) {
        // `--model auto`: every candidate's penalty (lower is closer to the photo).
        std::string scores;
        for (const ModelScore& s : d.provenance.model_choice)
            scores += (scores.empty() ? "" : ", ") + s.model + (s.colour == "pca" ? "" : "/" + s.colour) +
                      (s.variant.empty() ? "" : " [" + s.variant + "]") + info_text(" %.3f", s.penalty);
        out << "chosen by    auto (fidelity penalty: " << scores << ")\n";
    }
    out << "colour       " << to_string(d.colour_mode) << ", " << d.colour_space << "\n";
    out << "mean         " << info_text("%.5f %.5f %.5f", d.mean[0], d.mean[1], d.mean[2]) << "\n";
    for (int r = 0; r < 3; ++r)
        out << (r == 0 ? "basis        " : "             ") << info_text("%+.4f %+.4f %+.4f", d.basis[r][0], d.basis[r][1], d.basis[r][2])
            << "\n";
    for (int c = 0; c < 3; ++c) {
        out << "histogram " << c << "  ";
        if (!d.histograms[c].enabled()) {
            out << "off (Gaussian)\n";
            continue;
        }
        out << d.histograms[c].z.size() << " knots, values " << info_text("%.4f .. %.4f", d.histograms[c].value.front(), d.histograms[c].value.back())
            << "\n";
    }
    if (const ChromaGivenBrightness& joint = d.chroma_given_brightness; joint.enabled()) {
        const auto range = [](const std::vector<double>& v) {
            return info_text("%.4f .. %.4f", *std::min_element(v.begin(), v.end()), *std::max_element(v.begin(), v.end()));
        };
        out << "joint colour chroma given brightness, " << joint.z.size() << " knots; scale 1: " << range(joint.scale[0])
            << ", scale 2: " << range(joint.scale[1]) << "\n";
    }
    const Model& model = model_of(d);
    // The declared scalar parameters, as stored, with their units (the declaration says which
    // they are); arrays and objects are the model's own lines below.
    const json_fields::Json block = model.write_parameters(d);
    std::string scalars;
    for (const ParameterInfo& p : model.info().parameters) {
        if (!block.contains(p.key) || block[p.key].is_structured() || block[p.key].is_null()) continue;
        const json_fields::Json& value = block[p.key];
        std::string text = value.is_string() ? value.get<std::string>() : json_fields::format(value);
        if (!value.is_string()) text.pop_back();  // format() ends the document with a newline
        scalars += (scalars.empty() ? "" : ", ") + p.key + " " + text + (p.unit.empty() ? "" : " " + p.unit);
    }
    if (!scalars.empty()) out << "parameters   " << scalars << "\n";
    out << model.describe(d);
    const Rgb mean = make_texture(d)->mean();
    out << "texture mean " << info_text("%.5f %.5f %.5f", mean[0], mean[1], mean[2]) << " (limit of minification)\n";
    return out.str();
}

}  // namespace stochtex
