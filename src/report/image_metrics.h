#pragma once
#include <cstdint>
// Error metrics between an image and a reference, as used in rendering comparisons (the paper
// reports PSNR; relative MSE is the usual figure for Monte Carlo noise). Part of report/, as io/
// holds file formats only.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "io/image.h"

namespace snell {

/// Pixel rectangle [x, x+w) x [y, y+h); w == 0 means the whole image.
struct Crop {
    int x = 0, y = 0, w = 0, h = 0;
};

/// Whether `c` (w, h > 0) lies inside a width x height image. The sums are taken in 64 bits:
/// x + w overflowed int for x = 2147483647, and the crop passed (issue 12).
bool crop_inside(const Crop& c, int width, int height);
/// Throws std::invalid_argument "crop x,y,w,h is outside the WxH image" unless crop_inside().
void check_crop_inside(const Crop& c, int width, int height);

struct ImageMetrics {
    double rel_mse = 0;  ///< mean of (a - r)^2 / (r^2 + 0.01) over pixels and channels
    double mse = 0;
    double rmse = 0;
    double psnr = 0;                      ///< dB, on values clamped to [0, 1] (peak 1); inf for identical images
    double smape = 0;                     ///< mean of |a - r| / (|a| + |r| + 0.01), in [0, 1)
    double mean = 0, mean_reference = 0;  ///< mean values (all channels) of both images
    /// Per-pixel median of |Y(a) - Y(r)| / Y(r) (luminance), over pixels whose reference
    /// luminance exceeds 1e-4 of the region's mean: the typical error, which a few fireflies
    /// cannot dominate as they dominate relMSE.
    double median_rel_error = 0;
    /// The same per channel: median over pixels and channels of |a - r| / r.
    double median_rel_error_rgb = 0;
    long pixels = 0;
};

/// Metrics of `img` against `ref` over `crop`; relMSE divides by (r^2 + 0.01) with r from
/// `normaliser` where given (same size), else from `ref`. Throws std::invalid_argument on size
/// mismatch or a crop outside the image.
ImageMetrics compare_images(const Image& img, const Image& ref, const Crop& crop = {},
                            const Image* normaliser = nullptr);

/// The metrics as `snell diff --json` writes them (rel_mse, rmse, psnr, smape, mean,
/// mean_reference, median_rel_error, median_rel_error_rgb); found by nlohmann via ADL.
void to_json(nlohmann::json& j, const ImageMetrics& m);

/// Parses "x,y,w,h"; throws std::invalid_argument with the offending text.
Crop parse_crop(const std::string& text);

}  // namespace snell
