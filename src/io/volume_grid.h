#pragma once
// Mitsuba's binary volume grids (.vol, version 3): the data of a `gridvolume`.
#include <array>
#include <string>
#include <vector>

namespace snell {

struct VolumeGrid {
    int xres = 0, yres = 0, zres = 0;
    int channels = 0;
    std::array<float, 6> bbox{};  ///< the grid's box in the file: min x, y, z, max x, y, z
    std::vector<float> data;      ///< ((z yres + y) xres + x) channels + c
};

/// Reads a .vol file: "VOL", version 3, encoding 1 (float32), resolutions, channels, bounding
/// box, then the values. Throws std::runtime_error naming the path and what is wrong.
VolumeGrid read_volume_grid(const std::string& path);

}  // namespace snell
