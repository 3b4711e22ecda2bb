#include "bsdf/conductor_data.h"

#include <vector>

#include "bsdf/conductor_table.h"

namespace snell {

std::optional<ConductorIOR> named_conductor(const std::string& name) {
    for (const ConductorTableEntry& e : conductor_table())
        if (e.name == name)
            return ConductorIOR{Spectrum::tabulated(e.eta_lambda, e.eta), Spectrum::tabulated(e.k_lambda, e.k)};
    return std::nullopt;
}

std::string named_conductor_list() {
    std::string s = "none";
    for (const ConductorTableEntry& e : conductor_table()) s += ", " + e.name;
    return s;
}

}  // namespace snell
