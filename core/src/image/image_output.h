// stochtex — the one path by which pixels become an image file (rendered images, the ptm
// coefficient maps and normal maps): safely, and with every failed write reported.
#pragma once

#include <OpenImageIO/imageio.h>

#include <string>

namespace stochtex {

/// Writes `pixels` (spec.nchannels floats a pixel, top row first; stored as spec.format) with
/// `output`, made by ImageOutput::create(path) so that the final name chooses the format. The
/// file goes through an AtomicOutput (atomic_write.h): a failed write leaves the previous file
/// and no temporary. Throws Error "<path>: cannot write <what>: <reason>".
void write_pixels_atomically(OIIO::ImageOutput& output, const std::string& path, const OIIO::ImageSpec& spec,
                             const float* pixels, const std::string& what);

}  // namespace stochtex
