#pragma once
// Mitsuba integrator elements that snell renders with one of its own techniques: the `moment`
// and `aov` wrappers (the nested integrator renders; their extra outputs are not written) and
// the integrators of the Specular Manifold Sampling code (Zeltner et al. 2020: `path_sms_ss`,
// `path_sms_ms`, ...), which become `mnee` with the matching estimator. Each translation leaves
// a one-line notice of what differs; docs/scene-format.md has the table.
#include <string>
#include <vector>

#include "core/props.h"
#include "loader/xml_scene.h"

namespace snell {

/// The integrator that renders for `o`: `o` itself, or the one a `moment`/`aov` wrapper nests
/// (checked: exactly one), with a notice per wrapper when `notices` is given.
const XmlObject& unwrap_integrator(const XmlObject& o, std::vector<std::string>* notices);

/// The Props to create the integrator of `o` from, after unwrapping and translation; `notices`
/// receives "file:line: what differs" lines.
Props integrator_props(const XmlObject& o, std::vector<std::string>* notices);

/// Marks the SMS code's shape and emitter flags (caustic_receiver, caustic_caster_single, ...)
/// used: snell's MNEE finds its casters and receivers from the materials. True if any was set.
bool consume_sms_flags(const Props& p);

}  // namespace snell
