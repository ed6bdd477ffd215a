// stochtex — the one path by which pixels become an image file (rendered images, bakes, the ptm
// coefficient maps and normal maps, the OSL tables): the codec chosen by the final name
// (image_codec.h), safely, and with every failed write reported.
#pragma once

#include "image/image_codec.h"

#include <string>

namespace stochtex {

/// The codec that writes `path` (tiled_mip: as a tiled, MIP-mapped image). Throws Error
/// "<path>: cannot write <what>: '<ext>' is not an image format …" (check_image_output() gives
/// the same message before the work); `format`, if given, receives the format's name.
codec::ImageCodec& image_writer(const std::string& path, const std::string& what, bool tiled_mip = false,
                                std::string* format = nullptr);

/// Writes `pixels` (header.channels floats a pixel, top row first; stored as header.sample)
/// with the codec of `path`'s format, through an AtomicOutput (atomic_write.h): a failed write
/// leaves the previous file and no temporary. Throws Error "<path>: cannot write <what>: <reason>".
void write_image_file(const std::string& path, const codec::ImageHeader& header, const float* pixels,
                      const std::string& what);

}  // namespace stochtex
