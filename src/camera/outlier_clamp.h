#pragma once
// The outlier clamp of mnee's biased mode (issue 10) and its light spreading, as a post-process
// of a finished film (issue 27): apply_outlier_clamp runs once, after the last sample (after the
// reduction over MPI ranks, or the merge of partial films), and reads only what the film
// accumulated, so a distributed biased image equals the local one.
#include "camera/film.h"

namespace snell {

/// Clamps `film` (Film::set_outlier_clamp): a pixel's largest sample is scaled down so that it
/// carries at most the share `max_share` of the pixel's luminance, i.e. to s / (1 - s) times the
/// sum of the others. Biased, and consistent: with a finite mean the largest of n samples grows
/// slower than their sum, so the clamp stops acting as n grows. 0: off.
/// With `spread_radius` > 0 the light the clamp takes is not dropped but spread evenly over a
/// disc around its pixel (radius at most spread_radius pixels; the smallest that holds twice that
/// light from elsewhere, widened until its share of every pixel is at most `max_share` too): the
/// image keeps its light and the bias is a local blur of the fireflies. Only light that no such
/// disc hides, not even over the lit pixels alone (a lone firefly on black), is dropped, and only
/// at the pixels it would dominate. Applying it again replaces the earlier clamp.
void apply_outlier_clamp(Film& film, double max_share, int spread_radius = 0);

}  // namespace snell
