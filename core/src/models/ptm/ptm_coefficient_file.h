// The file beside a ptm .stex that holds its coefficient maps: a scanline OpenEXR, 32-bit float,
// ZIP-compressed, one channel per coefficient, named by ptm_channel_names() (docs/stex-format.md,
// "ptm"). The .stex records its size and a checksum, so a stale or foreign file is an error.
#pragma once

#include <stochtex/models/ptm.h>
#include <stochtex/models/ptm_parameters.h>

#include <string>

namespace stochtex {

/// Each side at most 4096 texels and at most 2^22 texels in all (≤ 302 MB of rgb floats).
constexpr int max_ptm_side = 4096;
constexpr long long max_ptm_texels = 1ll << 22;

/// "fnv1a64:<16 hex digits>": FNV-1a over the size and the float bits, in channel order.
std::string ptm_checksum(const PtmMaps& maps);

/// Reads and checks the maps; errors are "<what>: <problem>" (what names the .stex field).
PtmMaps read_ptm_coefficients(const std::string& path, PtmColour colour, const std::string& what);
/// Writes atomically (a temporary file beside it, then renamed).
void write_ptm_coefficients(const std::string& path, const PtmMaps& maps);

}  // namespace stochtex
