#include "camera/factory.h"

#include <cmath>

namespace snell {

std::shared_ptr<const Filter> create_filter(const Props& p) {
    auto positive = [&](const char* name, double def) {
        const double v = p.get_float(name, def);
        if (!(v > 0 && std::isfinite(v))) p.raise_param(name, std::string(name) + " must be positive");
        return v;
    };
    if (p.type() == "box") return box_filter();
    if (p.type() == "tent") return std::make_shared<TentFilter>(positive("radius", 1.0));
    if (p.type() == "gaussian") return std::make_shared<GaussianFilter>(positive("stddev", 0.5));
    p.raise("unknown rfilter type '" + p.type() + "' (accepted: box, gaussian, tent)");
}

}  // namespace snell
