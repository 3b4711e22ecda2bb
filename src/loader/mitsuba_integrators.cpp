#include "loader/mitsuba_integrators.h"

#include <set>

#include "loader/unsupported.h"

namespace snell {

namespace {

// The SMS code's integrators (tizian/specular-manifold-sampling, src/integrators/).
const std::set<std::string> kSmsIntegrators = {"path_sms_ss",      "path_sms_ms",      "path_sms_teaser",
                                               "path_filtered_ss", "path_filtered_ms", "path_filtered_teaser"};

// An SMS integrator as `mnee`. SMS's estimators map onto `solutions`: its unbiased one (the
// default) is solutions=unbiased; biased=true with max_trials M counts the distinct solutions of
// M trials, which is solutions=all with trials=M; mnee_init=true with max_trials=1 is the
// paper's MNEE (solutions=one), biased_mnee its outlier removal.
Props sms_as_mnee(const XmlObject& o_in, std::vector<std::string>* notices) {
    // The teaser integrators prefix the caustic settings with "caustics_" (and have glint ones
    // beside them): read caustics_X as X.
    XmlObject o = o_in;
    for (XmlParam& q : o.params)
        if (q.name.rfind("caustics_", 0) == 0 && !o_in.param(q.name.substr(9))) q.name = q.name.substr(9);
    Props in = object_props(o);
    Props out(o.tag, "mnee", o.loc);
    out.set_id(o.id);
    for (const char* name : {"max_depth", "rr_depth", "hide_emitters", "max_iterations", "timeout", "samples_per_pass"})
        if (const XmlParam* q = o.param(name)) {
            in.mark_used(name);
            out.set(name, q->value, q->loc);
        }
    const bool biased = in.get_bool("biased", false);
    const bool mnee_init = in.get_bool("mnee_init", false);
    const int64_t max_trials = in.get_int("max_trials", -1);
    std::string what;
    if (mnee_init) {
        out.set("solutions", std::string("one"), o.loc);
        if (in.get_bool("biased_mnee", false)) out.set("biased", true, o.loc);
        what = "the paper's MNEE (solutions=one)";
    } else if (biased) {
        out.set("solutions", std::string("all"), o.loc);
        out.set("seeding", std::string("straight+surface"), o.loc);
        if (max_trials > 0) out.set("trials", max_trials, o.loc);
        what = "SMS's biased estimator as solutions=all (distinct solutions of " +
               (max_trials > 0 ? std::to_string(max_trials) : std::string("16")) + " trials)";
    } else {
        out.set("solutions", std::string("unbiased"), o.loc);
        out.set("seeding", std::string("straight+surface"), o.loc);
        if (max_trials > 0) out.set("max_trials", max_trials, o.loc);
        what = "SMS's unbiased estimator as solutions=unbiased";
    }
    // What snell does its own way: always half-vector constraints (Hanika et al.), its own
    // convergence test and step control, every refractive shape a caster.
    std::string ignored;
    for (const char* name : {"halfvector_constraints",
                             "twostage",
                             "step_scale",
                             "solver_threshold",
                             "uniqueness_threshold",
                             "disable_reflected_emitters",
                             "biased_mnee",
                             "bounces",
                             "max_glints",
                             "caustics_filtered",
                             "glints",
                             "caustics",
                             "glints_filtered",
                             "non_sms_paths",
                             "crop_caustic",
                             "filter_radius",
                             "enabled",
                             "glints_enabled",
                             "glints_biased",
                             "glints_max_iterations",
                             "glints_max_trials",
                             "glints_solver_threshold",
                             "glints_uniqueness_threshold",
                             "glint_diff_scale_factor_clamp",
                             "non_sms_paths_enabled",
                             "multi_caustic_bounces"})
        if ((!mnee_init || std::string(name) != "biased_mnee") && in.mark_used(name))
            ignored += (ignored.empty() ? "" : ", ") + std::string(name);
    in.check_unused();
    std::string n = o.loc.str() + ": <integrator type=\"" + o.type + "\"> renders as mnee with " + what;
    if (o.type.rfind("path_filtered", 0) == 0)
        n += "; the filtered (roughened) variant is not built, this is unfiltered";
    if (o.type.find("_ms") != std::string::npos)
        n += "; chains of several specular interfaces are solved as one chain (snell's max_vertices)";
    if (!ignored.empty()) n += "; ignored: " + ignored;
    notices->push_back(n);
    return out;
}

// An integrator snell renders with another technique that converges to the same image: keeps
// the common settings, names the rest in the notice.
Props renamed(const XmlObject& o, const std::string& as, const std::string& why, std::vector<std::string>* notices) {
    static const std::set<std::string> kept = {"max_depth", "rr_depth", "hide_emitters", "timeout", "samples_per_pass"};
    Props out(o.tag, as, o.loc);
    out.set_id(o.id);
    std::string ignored;
    for (const XmlParam& q : o.params)
        if (kept.count(q.name))
            out.set(q.name, q.value, q.loc);
        else
            ignored += (ignored.empty() ? "" : ", ") + q.name;
    notices->push_back(o.loc.str() + ": <integrator type=\"" + o.type + "\"> renders as " + as + ": " + why +
                       (ignored.empty() ? "" : "; ignored: " + ignored));
    return out;
}

}  // namespace

const XmlObject& unwrap_integrator(const XmlObject& o_in, std::vector<std::string>* notices) {
    const XmlObject* o = &o_in;
    // Mitsuba's wrappers that add outputs around an inner integrator.
    while (o->type == "moment" || o->type == "aov") {
        const XmlObject* inner = nullptr;
        for (const auto& c : o->children)
            if (c.obj->tag == "integrator") {
                if (inner)
                    throw SceneError(c.obj->loc, "integrator",
                                     "a <integrator type=\"" + o->type + "\"> wraps one integrator (the first is at " +
                                         inner->loc.str() + ")");
                inner = c.obj.get();
            }
        if (!inner)
            throw SceneError(o->loc, "integrator",
                             "<integrator type=\"" + o->type + "\"> needs a nested <integrator> to render with");
        if (notices)
            notices->push_back(o->loc.str() + ": <integrator type=\"" + o->type + "\"> is unwrapped: its nested " +
                               "<integrator type=\"" + inner->type + "\"> renders, the " +
                               (o->type == "aov" ? "AOV" : "moment") + " images are not written");
        o = inner;
    }
    return *o;
}

Props integrator_props(const XmlObject& wrapped, std::vector<std::string>* notices) {
    const XmlObject* o = &unwrap_integrator(wrapped, notices);
    // An unsupported wrapper (stokes) says what it is before anything about its nesting.
    if (const std::string why = unsupported_feature(o->tag, o->type); !why.empty())
        throw SceneError(o->loc, o->tag, why);
    for (const auto& c : o->children)
        throw SceneError(c.obj->loc, c.obj->tag,
                         "<integrator type=\"" + o->type + "\"> takes no nested <" + c.obj->tag + ">");
    if (kSmsIntegrators.count(o->type)) return sms_as_mnee(*o, notices);
    std::vector<std::string> discard;
    if (!notices) notices = &discard;
    if (o->type == "ptracer")
        return renamed(*o, "bdpt",
                       "Mitsuba's particle tracer is bdpt's light-tracing strategy alone; bdpt converges to the "
                       "same image",
                       notices);
    if (o->type == "path_sms_glints")
        return renamed(*o, "path",
                       "glints of normal-mapped reflectors are found by BSDF sampling and emitter sampling "
                       "(no manifold technique for them): the same image in expectation, noisier for small lights",
                       notices);
    return object_props(*o);
}

bool consume_sms_flags(const Props& p) {
    bool any = false;
    for (const char* name : {"caustic_receiver", "caustic_caster_single", "caustic_caster_multi", "caustic_bouncer",
                             "caustic_emitter_single", "caustic_emitter_multi", "glinty"})
        any = p.mark_used(name) || any;
    return any;
}

}  // namespace snell
