#pragma once
// Named conductors (Mitsuba's `material` parameter of conductor/roughconductor).
#include <optional>
#include <string>

#include "core/spectrum.h"

namespace snell {

/// Complex IOR eta + i k of a conductor as tabulated spectra (wavelengths in nm).
struct ConductorIOR {
    Spectrum eta, k;
};

/// Measured complex IOR of a named conductor, by Mitsuba's names ("Au", "Ag", "Cu", "Al", "a-C",
/// "W", ...: the files of its ior/ data folder, conductor_table.h); std::nullopt for an unknown
/// name. "none" (a perfect mirror) is handled by the BSDFs, not here.
std::optional<ConductorIOR> named_conductor(const std::string& name);

/// Comma-separated list of the accepted names, for error messages.
std::string named_conductor_list();

}  // namespace snell
