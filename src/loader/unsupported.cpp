#include "loader/unsupported.h"

#include <map>
#include <utility>

namespace snell {

std::string unsupported_feature(const std::string& tag, const std::string& type) {
    static const std::map<std::pair<std::string, std::string>, std::string> table = {
        {{"bsdf", "polarizer"}, "polarisation is"},
        {{"bsdf", "retarder"}, "polarisation is"},
        {{"bsdf", "pplastic"}, "polarisation is"},
        {{"bsdf", "measured_polarized"}, "polarisation is"},
        {{"bsdf", "hair"}, "hair and curves are"},
        {{"bsdf", "measured"}, "measured (RGL) BSDFs are"},
        {{"shape", "linearcurve"}, "curves are"},
        {{"shape", "bsplinecurve"}, "curves are"},
        {{"shape", "sdfgrid"}, "SDF grids are"},
        {{"integrator", "volpath"}, "participating media are"},
        {{"integrator", "volpathmis"}, "participating media are"},
        {{"integrator", "prbvolpath"}, "participating media are"},
        {{"integrator", "stokes"}, "polarisation is"},
        {{"sensor", "radiancemeter"}, "radiance meters are"},
        {{"sensor", "irradiancemeter"}, "irradiance meters are"},
    };
    const auto it = table.find({tag, type});
    if (it == table.end()) return "";
    return "<" + tag + " type=\"" + type + "\">: " + it->second + " not supported by snell";
}

Props object_props(const XmlObject& o) {
    if (const std::string why = unsupported_feature(o.tag, o.type); !why.empty()) throw SceneError(o.loc, o.tag, why);
    Props p(o.tag, o.type, o.loc);
    p.set_id(o.id);
    for (const auto& q : o.params) p.set(q.name, q.value, q.loc);
    return p;
}

}  // namespace snell
