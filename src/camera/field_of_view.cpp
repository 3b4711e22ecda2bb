#include "camera/field_of_view.h"

#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>

namespace snell {

FieldOfView read_field_of_view(const Props& p) {
    FieldOfView f;
    f.axis = p.get_string("fov_axis", "x");
    static const std::set<std::string> axes = {"x", "y", "smaller", "larger", "diagonal"};
    if (!axes.count(f.axis)) p.raise_param("fov_axis", "fov_axis must be x, y, smaller, larger or diagonal");
    if (p.has("fov") && p.has("focal_length"))
        p.raise_param("focal_length", "give either 'fov' or 'focal_length', not both");
    if (p.has("fov")) {
        f.fov_deg = p.get_float("fov");
    } else {
        // A focal length on 35 mm film, whose diagonal (sqrt(36^2 + 24^2) mm) it spans: the
        // field of view is along the diagonal.
        std::string s = p.get_string("focal_length", "50mm");
        if (s.size() > 2 && s.compare(s.size() - 2, 2, "mm") == 0) s.resize(s.size() - 2);
        char* end = nullptr;
        const double mm = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || !(mm > 0) || !std::isfinite(mm))
            p.raise_param("focal_length", "focal_length must read like '50mm'");
        f.fov_deg = 2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)) * 180.0 / kPi;
        f.axis = "diagonal";
    }
    if (!(f.fov_deg > 0 && f.fov_deg < 180)) p.raise_param("fov", "fov must lie in (0, 180) degrees");
    return f;
}

Vec2 fov_tangents(const FieldOfView& fov, double aspect) {
    const double t = std::tan(0.5 * fov.fov_deg * kPi / 180.0);
    std::string axis = fov.axis;
    if (axis == "smaller") axis = aspect >= 1 ? "y" : "x";
    if (axis == "larger") axis = aspect >= 1 ? "x" : "y";
    if (axis == "x") return {t, t / aspect};
    if (axis == "y") return {t * aspect, t};
    if (axis == "diagonal") {
        const double d = std::sqrt(aspect * aspect + 1.0);
        return {t * aspect / d, t / d};
    }
    throw std::invalid_argument("unknown fov_axis '" + fov.axis + "' (x, y, smaller, larger, diagonal)");
}

}  // namespace snell
