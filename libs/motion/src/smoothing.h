// smoothing.h (private to layers::motion) -- smoothing of per-frame curves:
// Gaussian smoothing, smooth envelopes that stay above a curve (for
// corrections that must cover every frame that needs them) or below it
// (for limits they must respect), and filling gaps between known values.
#pragma once

#include <vector>

namespace layers::motion {

// Gaussian smoothing (sigma in frames, truncated at 3 sigma, ends clamped).
std::vector<double> gaussian_smooth(const std::vector<double>& v, double sigma);

// A max filter of radius ceil(3 sigma) followed by gaussian_smooth: smooth
// and >= v everywhere.
std::vector<double> upper_envelope(const std::vector<double>& v, double sigma);

// Its mirror: a min filter then gaussian_smooth, smooth and <= v everywhere
// (for limits a spread correction must stay under).
std::vector<double> lower_envelope(const std::vector<double>& v, double sigma);

// Linear interpolation over NaN runs; runs at the ends take the nearest
// value (`fallback` when all are NaN).
void fill_gaps(std::vector<double>& v, double fallback);

}  // namespace layers::motion
