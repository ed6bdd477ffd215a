// The `stex` sub-commands. Each returns the process exit code and throws stochtex::Error for
// bad input (main() prints it and exits 1). Option names are the public interface: later
// issues extend them, never rename them.
#pragma once

#include <stochtex/analysis.h>

#include <cstdint>
#include <string>

namespace stex_cli {

struct AnalyzeCommand {
    std::string photo, output;
    std::string model = "wavelet", colour = "pca", histogram = "auto", psd = "periodic";
    std::string colour_space;  // empty: what the file says, else sRGB
    int knots = 10;
    int bands = 0;
    std::string gabor_kind = "isotropic";
    double impulses = 16, bandwidth = 0;  // gabor; bandwidth 0: fitted
    int exemplar_size = 256, exemplar_bits = 8;  // tiling
    int lrp_cosines = 50, lrp_strata = 8;  // lrp: J, L
    double lrp_structure = 0.1;            // lrp: r
    std::string lrp_placement = "on", lrp_turbulence = "auto";
    std::uint32_t seed = 1;
    double unit_size_m = 1.0;
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
    int run() const;
};

struct InfoCommand {
    std::string texture;
    int run() const;
};

struct CompareCommand {
    std::string photo, texture, output;  // output: side-by-side PNG (optional)
    std::string colour_space;
    int run() const;
};

struct MorphCommand {
    std::string a, b, output;
    double t = 0.5;
    int run() const;
};

struct PovCommand {
    std::string texture, output, name;  // name empty: from the output file's name
    std::string mode;                   // empty: procedural where the model has that form, else baked
    int bake_size = 0;                  // baked: pixels per side; 0: one texture unit at the photo's scale
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
    int run() const;
};

struct OslCommand {
    std::string texture, output, name;  // name empty: from the output file's name
    std::string tile_dir;               // where the shader looks for the noise tiles; empty: beside the output
    int run() const;
};

/// Parses "WxH" (e.g. "1024x512"); throws Error naming the option.
std::pair<int, int> parse_size(const std::string& text, const char* option);

}  // namespace stex_cli
