// A list of object distances that are meant to be different planes (depthmap's sweep, its PSF
// stack, depth's analysis): two within kSameDistanceRelative of each other are one plane given
// twice. The magnification changes by that fraction between them, which moves a point at the edge
// of the largest capture (core/image kMaxImageSamples, 11585 px square: 8200 px from the centre)
// by 0.008 px, so no capture tells them apart. (Distances one float step apart passed as distinct.)
#pragma once

#include <string>
#include <vector>

namespace pinmask {

inline constexpr double kSameDistanceRelative = 1e-6;

// Throws InvalidInput naming `field`, both distances in full (17 digits) and both planes by their
// index in `distances` (the caller's order, any order accepted). Infinite distances are equal
// only to each other.
void check_distinct_distances(const std::vector<double>& distances, const std::string& field);

}  // namespace pinmask
