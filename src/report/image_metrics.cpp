#include "report/image_metrics.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace snell {

ImageMetrics compare_images(const Image& img, const Image& ref, const Crop& crop_in, const Image* normaliser) {
    for (const Image* other : {&ref, normaliser})
        if (other && (img.width != other->width || img.height != other->height))
            throw std::invalid_argument("image sizes differ: " + std::to_string(img.width) + "x" +
                                        std::to_string(img.height) + " vs " + std::to_string(other->width) + "x" +
                                        std::to_string(other->height));
    const Image& norm = normaliser ? *normaliser : ref;
    Crop c = crop_in;
    if (c.w == 0) c = {0, 0, img.width, img.height};
    check_crop_inside(c, img.width, img.height);
    ImageMetrics m;
    double rel = 0, se = 0, se_clamped = 0, smape = 0, sa = 0, sr = 0;
    for (int y = c.y; y < c.y + c.h; ++y)
        for (int x = c.x; x < c.x + c.w; ++x)
            for (int ch = 0; ch < 3; ++ch) {
                const double a = img.at(x, y, ch), r = ref.at(x, y, ch), d = a - r, q = norm.at(x, y, ch);
                rel += d * d / (q * q + 0.01);
                se += d * d;
                se_clamped += std::pow(std::clamp(a, 0.0, 1.0) - std::clamp(r, 0.0, 1.0), 2);
                smape += std::abs(d) / (std::abs(a) + std::abs(r) + 0.01);
                sa += a;
                sr += r;
            }
    const double n = 3.0 * c.w * c.h;
    m.pixels = long(c.w) * c.h;
    m.rel_mse = rel / n;
    m.mse = se / n;
    m.rmse = std::sqrt(m.mse);
    m.psnr = se_clamped > 0 ? 10.0 * std::log10(n / se_clamped) : std::numeric_limits<double>::infinity();
    m.smape = smape / n;
    m.mean = sa / n;
    m.mean_reference = sr / n;
    // Medians of relative errors, skipping (near-)black reference pixels.
    const auto luminance = [](const Image& im, int x, int y) {
        return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
    };
    const double floor_value = 1e-4 * std::max(m.mean_reference, 1e-300);
    std::vector<double> lum, rgb;
    for (int y = c.y; y < c.y + c.h; ++y)
        for (int x = c.x; x < c.x + c.w; ++x) {
            const double yr = luminance(ref, x, y);
            if (yr > floor_value) lum.push_back(std::abs(luminance(img, x, y) - yr) / yr);
            for (int ch = 0; ch < 3; ++ch) {
                const double r = ref.at(x, y, ch);
                if (r > floor_value) rgb.push_back(std::abs(img.at(x, y, ch) - r) / r);
            }
        }
    const auto median = [](std::vector<double>& v) {
        if (v.empty()) return 0.0;
        std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    m.median_rel_error = median(lum);
    m.median_rel_error_rgb = median(rgb);
    return m;
}

bool crop_inside(const Crop& c, int width, int height) {
    return c.x >= 0 && c.y >= 0 && c.w > 0 && c.h > 0 && int64_t(c.x) + c.w <= width && int64_t(c.y) + c.h <= height;
}

void check_crop_inside(const Crop& c, int width, int height) {
    if (!crop_inside(c, width, height))
        throw std::invalid_argument("crop " + std::to_string(c.x) + "," + std::to_string(c.y) + "," +
                                    std::to_string(c.w) + "," + std::to_string(c.h) + " is outside the " +
                                    std::to_string(width) + "x" + std::to_string(height) + " image");
}

Crop parse_crop(const std::string& text) {
    Crop c;
    char s1, s2, s3;
    std::istringstream in(text);
    if (!(in >> c.x >> s1 >> c.y >> s2 >> c.w >> s3 >> c.h) || s1 != ',' || s2 != ',' || s3 != ',' || !in.eof() ||
        c.x < 0 || c.y < 0 || c.w <= 0 || c.h <= 0)
        throw std::invalid_argument("crop must be x,y,w,h (pixels; x, y >= 0, w, h >= 1), got '" + text + "'");
    return c;
}

void to_json(nlohmann::json& j, const ImageMetrics& m) {
    j = {{"rel_mse", m.rel_mse},
         {"rmse", m.rmse},
         {"psnr", m.psnr},
         {"smape", m.smape},
         {"mean", m.mean},
         {"mean_reference", m.mean_reference},
         {"median_rel_error", m.median_rel_error},
         {"median_rel_error_rgb", m.median_rel_error_rgb}};
}

}  // namespace snell
