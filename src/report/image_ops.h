#pragma once
// Small image manipulations for reports: cutting out a crop and enlarging it without smoothing,
// so that individual noisy pixels stay visible (the paper's inset crops).
#include "io/image.h"
#include "report/image_metrics.h"

namespace snell {

/// The pixels of `crop` as a new image (w == 0: a copy of the whole image). Throws
/// std::invalid_argument when the crop leaves the image.
Image crop_image(const Image& img, const Crop& crop);

/// Each pixel repeated `factor` x `factor` times (nearest-neighbour scaling); factor >= 1.
Image upscale_nearest(const Image& img, int factor);

/// Integer enlargement that brings the longer side of a w x h crop near `target` pixels
/// (at least 1, at most 16).
int enlargement_factor(int w, int h, int target = 256);

}  // namespace snell
