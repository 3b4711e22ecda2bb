#include "integrators/path/path_settings.h"

#include "core/props.h"

namespace snell {

PathSettings PathSettings::from_props(const Props& props) {
    PathSettings s;
    s.max_depth = int(props.get_int("max_depth", -1));
    s.rr_depth = int(props.get_int("rr_depth", 5));
    s.hide_emitters = props.get_bool("hide_emitters", false);
    s.hide_specular_emitters = props.get_bool("hide_specular_emitters", false);
    if (s.max_depth < -1 || s.max_depth == 0) props.raise_param("max_depth", "must be -1 (unbounded) or >= 1");
    if (s.rr_depth < 1) props.raise_param("rr_depth", "must be >= 1");
    return s;
}

PathSettings PathSettings::tracer_from_props(const Props& props) {
    PathSettings s = from_props(props);
    s.max_sample_share = props.get_float("max_sample_share", 0.0);
    if (!(s.max_sample_share >= 0 && s.max_sample_share < 1))
        props.raise_param("max_sample_share", "must lie in [0, 1) (0: no clamp)");
    const int64_t spread = props.get_int("clamp_spread", 0);
    if (spread < 0 || spread > 255)
        props.raise_param("clamp_spread", "must lie in [0, 255] pixels (0: the clamped light is dropped)");
    s.clamp_spread = int(spread);
    s.caster_probability = props.get_float("caster_probability", 0.0);
    if (!(s.caster_probability >= 0 && s.caster_probability < 1))
        props.raise_param("caster_probability", "must lie in [0, 1) (0: BSDF sampling alone)");
    return s;
}

}  // namespace snell
