// The `stex` sub-commands built into the tool. Each declares its options (add_options) and
// registers itself (command_registry.h) beside its run() in commands.cpp; run() returns the
// process exit code and throws stochtex::Error for bad input (main() prints it and exits 1). Option names are the public interface: later
// issues extend them, never rename them.
#pragma once

#include <stochtex/analysis.h>

#include <CLI/CLI.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace stex_cli {

struct AnalyzeCommand {
    std::string photo, output;
    std::string model = stochtex::automatic_model, colour = "pca", histogram = "auto";
    std::string joint_colour = "auto";
    bool choice_structure = false;  // --choice-structure
    std::string colour_space;  // empty: what the file says, else sRGB
    int knots = 10;
    int bands = 0;
    std::uint32_t seed = 1;
    double unit_size_m = 1.0;
    CLI::Option* colour_option = nullptr;  ///< to tell whether --colour was given
    /// Adds every registered model's declared analysis options (--psd, --impulses, --J, …).
    void add_model_options(CLI::App& command);
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;

private:
    /// Per declared option name: its value and the CLI11 option (to tell whether it was given).
    std::map<std::string, std::pair<std::string, CLI::Option*>> model_options_;
};

/// Numeric option checks: a finite number > 0 (≥ 0). CLI11's PositiveNumber/NonNegativeNumber
/// let NaN through and print their range with DBL_MAX written out in full (309 digits).
CLI::Validator positive_number();
CLI::Validator non_negative_number();

/// Names of the registered models that analyse photos, and the --model help built from them.
std::vector<std::string> analysable_models();
std::string model_option_help();

struct ModelsCommand {
    bool json = false, markdown = false;
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;
};

struct RenderCommand {
    std::string texture, output;
    std::string size;       // "WxH"; empty: the photo's size, else 512x512
    double scale = 1.0;     // exemplar pixels per output pixel
    double origin_u = 0, origin_v = 0;
    bool solid = false;
    double z = 0;
    bool no_filter = false;
    bool tileable = false;  // the image is one period of a periodic texture
    int threads = 0;
    std::int64_t seed = -1; // -1: the texture's own seed
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;
};

struct InfoCommand {
    std::string texture;
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;
};

struct CompareCommand {
    std::string photo, texture, output;  // output: side-by-side PNG (optional)
    std::string colour_space;
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;
};

struct MorphCommand {
    std::string a, b, output;
    double t = 0.5;
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;
};

struct PovCommand {
    std::string texture, output, name;  // name empty: from the output file's name
    std::string mode;                   // empty: procedural where the model has that form, else baked
    int bake_size = 0;                  // baked: pixels per side; 0: one texture unit at the photo's scale
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;
};

struct BakeCommand {
    std::string texture, output;
    int size = 1024;         // level-0 texels per side
    double scale = 1.0;      // exemplar pixels per texel
    int tile = 64;
    bool half = false;
    int threads = 0;
    std::int64_t seed = -1;  // -1: the texture's own seed
    std::string positions;   // non-empty: bake the solid texture at this position map's texels
    double position_scale = 1.0;  // texture units per position unit
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;
};

struct OslCommand {
    std::string texture, output, name;  // name empty: from the output file's name
    std::string tile_dir;               // where the shader looks for the noise tiles; empty: beside the output
    /// Declares its options on its sub-command (commands.cpp, beside run()).
    void add_options(CLI::App& command);
    int run() const;
};

/// Parses "WxH" (e.g. "1024x512"); throws Error naming the option.
std::pair<int, int> parse_size(const std::string& text, const char* option);

}  // namespace stex_cli
