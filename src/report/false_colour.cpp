#include "report/false_colour.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace snell {

Rgb8 viridis(double t) {
    // Nine evenly spaced samples of matplotlib's viridis (t = 0, 1/8, ..., 1), sRGB 8-bit.
    static constexpr uint8_t table[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                            {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                            {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
    if (std::isnan(t)) t = 1.0;
    t = std::clamp(t, 0.0, 1.0) * 8.0;
    const int i = std::min(int(t), 7);
    const double f = t - i;
    Rgb8 c;
    for (int k = 0; k < 3; ++k) c[k] = uint8_t(std::lround(table[i][k] + f * (table[i + 1][k] - table[i][k])));
    return c;
}

double pixel_relative_error(const Image& img, const Image& ref, int x, int y) {
    double sum = 0;
    for (int ch = 0; ch < 3; ++ch) {
        const double a = img.at(x, y, ch), r = ref.at(x, y, ch), d = a - r;
        sum += d * d / (r * r + 0.01);
    }
    return std::sqrt(sum / 3.0);
}

void write_png_rgb8(const std::string& path, int width, int height, const uint8_t* rgb) {
    if (width <= 0 || height <= 0 || !stbi_write_png(path.c_str(), width, height, 3, rgb, width * 3))
        throw std::runtime_error("cannot write PNG '" + path + "' (" + std::to_string(width) + "x" +
                                 std::to_string(height) + ", unwritable path or empty image)");
}

void write_relative_error_png(const std::string& path, const Image& img, const Image& ref, double max_error) {
    if (img.width != ref.width || img.height != ref.height)
        throw std::invalid_argument("error image: sizes differ (" + std::to_string(img.width) + "x" +
                                    std::to_string(img.height) + " vs " + std::to_string(ref.width) + "x" +
                                    std::to_string(ref.height) + ")");
    std::vector<uint8_t> bytes(size_t(img.width) * img.height * 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const Rgb8 c = viridis(pixel_relative_error(img, ref, x, y) / max_error);
            std::copy(c.begin(), c.end(), bytes.begin() + (size_t(y) * img.width + x) * 3);
        }
    write_png_rgb8(path, img.width, img.height, bytes.data());
}

}  // namespace snell
