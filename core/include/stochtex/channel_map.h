// stochtex — how a decorrelated channel's Gaussian noise becomes its value, for front-ends that
// rebuild the colour stage in another renderer's language (POV-Ray colour maps, later Blender
// colour ramps and OSL splines).
//
// The core's colour stage (colour_mapping.h) is rgb = mean + basis · y with, per decorrelated
// channel c, y_c = f_c(z_c): z_c = m_c/σ_M the channel's noise normalised to unit variance and f_c
// its histogram map (σ_M·z when the map is off). f_c is a monotone cubic; renderers offer
// piecewise-linear ramps, so this header hands them a polyline that is provably close to it.
#pragma once

#include <stochtex/texture_description.h>

#include <array>
#include <vector>

namespace stochtex {

/// σ_M of decorrelated channel `channel` (eq. 2 for wavelet): the standard deviation of the
/// model's Gaussian noise m_c before its histogram map. Throws Error for an unknown model.
double channel_sigma(const TextureDescription& description, int channel);

/// f_c(z) of the unfiltered texture: the histogram map at z, or σ_M·z when the map is off.
double channel_value(const TextureDescription& description, int channel, double z);

/// A polyline (z_k, f_c(z_k)) over [z_min, z_max], z_k increasing, whose linear interpolation is
/// within `tolerance` of f_c everywhere in the range (checked at 32 points per segment; segments
/// are halved where they are not). It holds the histogram's knots inside the range, so a map
/// that is linear between knots costs no extra points; a map that is off is a single segment.
/// Throws Error if more than max_points would be needed or the arguments are invalid.
std::vector<std::array<double, 2>> channel_value_polyline(const TextureDescription& description, int channel,
                                                          double z_min, double z_max, double tolerance,
                                                          int max_points);

}  // namespace stochtex
