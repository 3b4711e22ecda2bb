#pragma once

namespace snell {

/// A rectangle of pixels of the film's output window, half-open: [x0, x1) x [y0, y1).
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool contains(int x, int y) const { return x >= x0 && y >= y0 && x < x1 && y < y1; }
    bool operator==(const PixelRect&) const = default;
};

}  // namespace snell
