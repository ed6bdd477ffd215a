// stochtex — multiresolution wavelet noise by example: the parameters block of a wavelet .stex (models/wavelet/).
// The declaration of these fields (keys, ranges, defaults, docs) is the model's parameter schema,
// in core/src/models/wavelet/; docs/stex-format.md lists it.
#pragma once

#include <array>
#include <vector>

namespace stochtex {

/// Multiresolution wavelet noise by example (paper 000).
struct WaveletParameters {
    /// band_weights[c][j]: weight of band j for channel c. Band j = 0 is the finest: its
    /// frequencies lie in [1/4, 1/2) cycles per exemplar pixel; band j covers [2^-(j+2), 2^-(j+1)).
    std::array<std::vector<double>, 3> band_weights;
};

}  // namespace stochtex
