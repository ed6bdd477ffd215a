// stochtex — the one path by which pixels become an image file (rendered images, the ptm
// coefficient maps and normal maps): safely, and with every failed write reported.
#pragma once

#include <OpenImageIO/imageio.h>

#include <memory>
#include <string>

namespace stochtex {

/// ImageOutput::create(path): the format chosen by the final name. Throws Error "<path>: cannot
/// write <what>: '<ext>' is not an image format …" (check_image_output() gives the same message
/// before the work).
std::unique_ptr<OIIO::ImageOutput> create_image_output(const std::string& path, const std::string& what);

/// Writes `pixels` (spec.nchannels floats a pixel, top row first; stored as spec.format) with
/// `output`, made by ImageOutput::create(path) so that the final name chooses the format. The
/// file goes through an AtomicOutput (atomic_write.h): a failed write leaves the previous file
/// and no temporary. Throws Error "<path>: cannot write <what>: <reason>".
void write_pixels_atomically(OIIO::ImageOutput& output, const std::string& path, const OIIO::ImageSpec& spec,
                             const float* pixels, const std::string& what);

}  // namespace stochtex
