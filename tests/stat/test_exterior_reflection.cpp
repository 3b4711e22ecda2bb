// The reflected connection (manifold/exterior_reflection.h, issue 26): light reflected once off
// the outside of glass, smooth or rough, connected by a manifold walk from its own seed.
// - At fixed receivers, its estimate of that light agrees with an independent estimator written
//   here by hand (cosine directions from the floor, a mirror reflection at the sphere weighted by
//   Fresnel's reflectance, the light hit on the part of it x_b sees, where the connection's light
//   points lie): the measurement, the Jacobians and the caster's probability are right.
// - Alg. 2's density replays the connection: for every path it found, density() gives the
//   density the connection reported, and the path obeys the law of reflection (at rough glass,
//   the half vector drawn from D).
// - In the `mnee` integrator, MIS between it and BSDF sampling (and NEE from rough glass) keeps
//   the image: renders with and without it agree per block.
// - The MIS cutoff cuts the connection and its density alike.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "bsdf/fresnel.h"
#include "integrators/mis.h"
#include "integrators/mnee/mnee_path.h"
#include "manifold/caster_choice.h"
#include "manifold/exterior_reflection.h"
#include "manifold/manifold_technique.h"
#include "sampler/independent.h"
#include "stat/droplet_points.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// Two glass spheres of high index (F0 = 0.18, so the reflection carries light worth testing) on
// a diffuse floor, lit by a sphere light large enough for BSDF sampling to converge.
const char* const kSmoothGlass =
    R"(<bsdf type="dielectric"><float name="int_ior" value="2.5"/><float name="ext_ior" value="1"/></bsdf>)";
// Rough glass (the demo's droplet has alpha 0.02): the light's image in it is a bright spot that NEE
// from y and BSDF sampling both hit, the wider the more often.
std::string rough_glass(const char* alpha) {
    return std::string(
               R"(<bsdf type="roughdielectric"><string name="distribution" value="beckmann"/><float name="alpha" value=")") +
           alpha + R"("/><float name="int_ior" value="2.5"/><float name="ext_ior" value="1"/></bsdf>)";
}

std::string two_spheres(const std::string& integrator = R"(<integrator type="mnee"/>)",
                        const std::string& glass = kSmoothGlass) {
    std::string xml = R"(<scene version="3.0.0">$integrator
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0,4.5,5" target="0,0,-0.3" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="18"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="5"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.5, 0.5"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0" y="0.8" z="0"/><float name="radius" value="0.8"/>
    $glass</shape>
  <shape type="sphere"><point name="center" x="-1" y="0.4" z="1.2"/><float name="radius" value="0.4"/>
    $glass</shape>
  <shape type="sphere"><point name="center" x="-2.2" y="2.6" z="-1.6"/><float name="radius" value="0.6"/>
    <emitter type="area"><rgb name="radiance" value="6, 6, 6"/></emitter></shape>
</scene>)";
    xml.replace(xml.find("$integrator"), 11, integrator);
    for (int i = 0; i < 2; ++i) xml.replace(xml.find("$glass"), 6, glass);
    return xml;
}

void replace_in(std::string& s, const std::string& what, const std::string& with) {
    ASSERT_NE(s.find(what), std::string::npos) << what;
    s.replace(s.find(what), what.size(), with);
}

// The reflected light at x_b by hand: a cosine direction, a mirror reflection off a glass sphere's
// outside weighted by Fresnel's reflectance, then the light. f cos / p of a Lambertian floor is
// its albedo.
double by_hand(const Scene& scene, const SurfaceInteraction& xb, const SampledWavelengths& wl, Sampler& smp) {
    const Vec2 u = smp.next_2d();
    const double r = std::sqrt(u.x), phi = 2 * kPi * u.y;
    const Vec3 local(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u.x)));
    const Frame frame = Frame::from_normal(xb.n);
    Ray ray = scene.spawn_ray(xb, frame.to_world(local));
    SurfaceInteraction y;
    if (!scene.intersect(ray, &y) || y.emitter() || !is_manifold_interface(y.bsdf(), wl[0])) return 0;
    if (!(dot(ray.d, y.ng) < 0)) return 0;  // the outside alone
    const double cos_i = -dot(ray.d, y.n);
    const double R = fresnel_dielectric(cos_i, y.bsdf()->eta(wl[0])).R;
    ray = scene.spawn_ray(y, ray.d + y.n * (2 * cos_i));
    SurfaceInteraction l;
    if (!scene.intersect(ray, &l) || !l.emitter()) return 0;
    // The connection draws its light point as NEE from x_b does (the sphere light's cap in sight
    // of x_b); the rest of the light, seen only from y, is BSDF sampling's alone.
    if (!(dot(xb.p - l.p, l.ng) > 0)) return 0;
    return 0.5 * R * l.emitter()->le(l.p, l.n, l.uv, -ray.d, wl)[0];
}

}  // namespace

TEST(ExteriorReflection, AgreesWithAMirrorTracedByHand) {
    const LoadedScene ls = load_xml(two_spheres());
    const Scene& scene = *ls.scene;
    MneeSettings st;
    st.exterior_reflections = 1;
    const ExteriorReflection technique(scene, st);
    const SampledWavelengths wl = SampledWavelengths::single(550);
    // Floor points on the light's side of the spheres, where their reflections land; at each the
    // connection draws its caster between the two.
    const Vec3 points[] = {{-1.2, 0, -0.9}, {-0.4, 0, -1.5}, {-1.7, 0, 0.7}, {-1.5, 0, 0.3}};
    int checked = 0;
    for (const Vec3& at : points) {
        const SurfaceInteraction xb = droplet_receiver(scene, at.x, at.z);
        ASSERT_LT(std::abs(xb.p.y), 1e-6);
        ASSERT_EQ(CasterChoice(scene, xb.p, 550).size(), 2u);
        IndependentSampler smp(31 + uint64_t(checked));
        smp.start_pixel_sample(0, 0, 0);
        Mean mine, hand;
        const ManifoldQuery q{&xb, xb.bsdf(), BSDFContext{wl, TransportMode::Radiance}, MediumStack(), false};
        for (int n = 0; n < 200000; ++n) {
            const ReflectedConnection r = technique.connect(q, smp);
            mine.add(r.found ? r.value[0] : 0.0);
        }
        for (int n = 0; n < 12000000; ++n) hand.add(by_hand(scene, xb, wl, smp));
        const double z = std::abs(mine.mean() - hand.mean()) / std::hypot(mine.stderr_(), hand.stderr_());
        std::cout << "[reflected] x_b (" << at.x << ", " << at.z << "): connection " << mine.mean() << " +- "
                  << mine.stderr_() << ", by hand " << hand.mean() << " +- " << hand.stderr_() << " (z " << z << ")\n";
        EXPECT_GT(hand.mean(), 10 * hand.stderr_()) << "the point receives reflected light worth testing";
        EXPECT_LT(z, 4.5);
        // Its relative error is below the hand estimator's at a sixtieth of the samples.
        EXPECT_LT(mine.stderr_() / mine.mean(), hand.stderr_() / hand.mean());
        ++checked;
    }
}

namespace {

// Alg. 2's density replays the connection: for every path connect() finds, density() gives the
// density it reported. At smooth glass y obeys the law of reflection; at rough glass y's half
// vector is the one drawn from D, off the normal, and density() finds the path only when its
// walk aims at that half vector too.
void density_replays_the_connection(const std::string& glass, bool rough) {
    const LoadedScene ls = load_xml(two_spheres(R"(<integrator type="mnee"/>)", glass));
    const Scene& scene = *ls.scene;
    MneeSettings st;
    st.exterior_reflections = 0.5;  // the density counts rho
    const ExteriorReflection technique(scene, st);
    const SampledWavelengths wl = SampledWavelengths::single(550);
    IndependentSampler smp(5);
    smp.start_pixel_sample(0, 0, 0);
    int found = 0, on_small = 0, off_mirror = 0, nee_weighs = 0;
    double max_w_nee = 0;
    for (int n = 0; n < 4000; ++n) {
        const Vec2 u = smp.next_2d();
        const SurfaceInteraction xb = droplet_receiver(scene, -1.5 + 3.5 * u.x, -2.5 + 3.5 * u.y);
        if (!xb.bsdf() || is_manifold_interface(xb.bsdf(), 550) || std::abs(xb.p.y) > 1e-6) continue;
        const ManifoldQuery q{&xb, xb.bsdf(), BSDFContext{wl, TransportMode::Radiance}, MediumStack(), false};
        const ReflectedConnection r = technique.connect(q, smp);
        if (!r.found) continue;
        ++found;
        on_small += r.y.shape == scene.manifold_casters()[1];
        // The law of reflection at y: its normal bisects the directions to x_b and x_c.
        const Vec3 h = normalize(normalize(xb.p - r.y.p) + normalize(r.lp.p - r.y.p));
        if (!rough) EXPECT_GT(dot(h, r.y.n), 1 - 1e-9);
        off_mirror += dot(h, r.y.n) < 1 - 1e-6;
        EXPECT_EQ(r.pdf_nee > 0, rough) << "NEE from y competes at rough glass alone";
        if (rough) {
            // NEE's density of the path, composed here: a cosine direction at the floor, y's area,
            // then the light point as the light samples it from y.
            const Vec3 to_y = r.y.p - xb.p;
            const double d2 = length_squared(to_y);
            const Vec3 o_b = to_y / std::sqrt(d2);
            const double p_nee = std::abs(dot(xb.n, o_b)) / kPi * std::abs(dot(r.y.ng, o_b)) / d2 * r.pmf *
                                 r.light->pdf_point(r.y.p, r.lp.p, r.lp.n);
            EXPECT_NEAR(r.pdf_nee, p_nee, 1e-6 * p_nee);
            // The connection weighs both other techniques: with the weights NEE from y and BSDF
            // sampling give the path (their densities checked here and by density()), they sum to 1.
            const double w_nee = power_heuristic(r.pdf_nee, {r.density, r.pdf_bsdf});
            const double w_bsdf = power_heuristic(r.pdf_bsdf, {r.density, r.pdf_nee});
            EXPECT_NEAR(reflected_connection_weight(r) + w_nee + w_bsdf, 1.0, 1e-12);
            nee_weighs += w_nee > 1e-9;
            max_w_nee = std::max(max_w_nee, w_nee);
        }
        const double d = technique.density(xb, *xb.bsdf(), MediumStack(), r.y, *r.light, r.pmf, r.lp.p, r.lp.n, 550);
        EXPECT_NEAR(d, r.density, 1e-6 * r.density);
        // From inside glass the technique makes no connection, so the density is 0 there.
        MediumStack inside;
        inside.cross(nullptr, true);
        EXPECT_EQ(technique.density(xb, *xb.bsdf(), inside, r.y, *r.light, r.pmf, r.lp.p, r.lp.n, 550), 0.0);
    }
    std::cout << "[reflected] " << (rough ? "rough" : "smooth") << ": " << found << " connections, " << on_small
              << " off the small sphere, " << off_mirror << " off the mirror direction";
    if (rough) std::cout << ", NEE from y weighs " << nee_weighs << " of them (its weight up to " << max_w_nee << ")";
    std::cout << "\n";
    EXPECT_GT(found, 400);
    EXPECT_GT(on_small, 50);
    if (rough) EXPECT_GT(off_mirror, found * 9 / 10);
    if (rough) EXPECT_GT(nee_weighs, found / 10) << "too few paths where NEE's weight shows";
}

}  // namespace

TEST(ExteriorReflection, DensityReplaysTheConnection) { density_replays_the_connection(kSmoothGlass, false); }

TEST(ExteriorReflection, DensityReplaysTheConnectionAtRoughGlass) {
    density_replays_the_connection(rough_glass("0.05"), true);
}

namespace {

// The integrator's MIS between the reflected connection and BSDF sampling (emitter_weight) keeps
// the image: the same scene with the connection off leaves that light to BSDF sampling alone. The
// camera sees a patch of floor that a black disc shades from the light, so that most of its
// light is the light the spheres reflect. Once with MNEE in every region (q = 1), once with the
// learned allocation, whose regions there take q = 0: there the suffix keeps x_b and its first
// vertex for the reflected class alone (MneePath::arrive), and the weights are otherwise the
// path tracer's.
// At rough glass NEE from y is the third technique, weighed against the connection in
// connect_at_interface.
void mnee_agrees_with_and_without_it(const std::string& glass) {
    const auto scene = [&](const char* rho, const std::string& allocation) {
        std::string xml = two_spheres(std::string(R"(<integrator type="mnee">)") + allocation +
                                          R"(<float name="exterior_reflections" value=")" + rho + R"("/></integrator>)",
                                      glass);
        // The patch around (-1.2, 0, -0.9), seen from above, and the disc between it and the light.
        replace_in(xml, R"(<lookat origin="0,4.5,5" target="0,0,-0.3" up="0,1,0"/>)",
                   R"(<lookat origin="-0.7,2.6,0.4" target="-1.2,0,-0.9" up="0,1,0"/>)");
        replace_in(xml, R"(<float name="fov" value="40"/>)", R"(<float name="fov" value="9"/>)");
        // A darker floor: the light it passes on to itself falls by its albedo squared, the
        // reflected light by its albedo alone.
        replace_in(xml, R"(<rgb name="reflectance" value="0.5, 0.5, 0.5"/>)",
                   R"(<rgb name="reflectance" value="0.2, 0.2, 0.2"/>)");
        replace_in(xml, "</scene>", R"(<shape type="disk"><transform name="to_world"><scale value="0.5"/>
      <lookat origin="-1.5,0.78,-1.11" target="-2.2,2.6,-1.6" up="0,1,0"/></transform>
      <bsdf type="diffuse"><rgb name="reflectance" value="0, 0, 0"/></bsdf></shape></scene>)");
        return xml;
    };
    const std::string fixed = R"(<string name="allocation" value="fixed"/>)";
    const std::string learned = R"(<integer name="allocation_block" value="8"/><integer name="pilot_spp" value="2"/>)";
    for (const std::string& allocation : {fixed, learned}) {
        const std::string what = allocation == fixed ? "q = 1" : "learned q";
        const LoadedScene a = load_xml(scene("0.3", allocation)), b = load_xml(scene("0", allocation));
        if (allocation == learned) {
            const std::vector<uint64_t> regions = allocation_regions(a, 4, "reflected, " + what);
            ASSERT_FALSE(regions.empty());
            EXPECT_GT(regions[0], 0u) << "no region at q = 0: the test would not see its weights";
        }
        const auto ea = block_estimates(a, *a.integrator, 160, 8, 6, 300);
        const auto eb = block_estimates(b, *b.integrator, 160, 8, 6, 400);
        const Estimate wa = whole_image(ea), wb = whole_image(eb);
        std::cout << "[reflected] " << what << ": shaded patch with the connection " << wa.mean << " +- " << wa.stderr_
                  << ", without " << wb.mean << " +- " << wb.stderr_ << "\n";
        expect_agreement(ea, eb, 0.01, ("mnee with the reflected connection against without it, " + what).c_str());
        EXPECT_LT(std::abs(wa.mean - wb.mean), 4 * std::hypot(wa.stderr_, wb.stderr_)) << what << ": the whole patch";
    }
}

}  // namespace

TEST(ExteriorReflection, MneeAgreesWithAndWithoutIt) { mnee_agrees_with_and_without_it(kSmoothGlass); }

TEST(ExteriorReflection, MneeAgreesWithAndWithoutItAtRoughGlass) {
    mnee_agrees_with_and_without_it(rough_glass("0.2"));
}

// The MIS cutoff (mis_cutoff.h) cuts both sides of a path alike: where BSDF sampling's density
// exceeds the ratio times the connection's, connect() delivers nothing and density() answers 0
// for BSDF sampling's copy of the path; elsewhere both keep the path. Were only one side cut, the
// cut paths would count twice (connect() uncut) or lose the connection's share (density() uncut).
// The ratio is the median of the paths' own, so about half of them are cut.
TEST(ExteriorReflection, CutoffCutsBothSidesAlike) {
    const LoadedScene ls = load_xml(two_spheres());
    const Scene& scene = *ls.scene;
    MneeSettings uncut;
    uncut.exterior_reflections = 0.5;
    uncut.mis_cutoff = 0;
    const SampledWavelengths wl = SampledWavelengths::single(550);
    const auto receiver = [&](int n) {
        IndependentSampler smp(900 + uint64_t(n));
        smp.start_pixel_sample(0, 0, 0);
        const Vec2 u = smp.next_2d();
        return droplet_receiver(scene, -1.5 + 3.5 * u.x, -2.5 + 3.5 * u.y);
    };
    // The same connection twice: each from a sampler of its own seed, so both draw alike.
    const auto connect = [&](const ExteriorReflection& t, const SurfaceInteraction& xb, int n) {
        IndependentSampler smp(7000 + uint64_t(n));
        smp.start_pixel_sample(0, 0, 0);
        const ManifoldQuery q{&xb, xb.bsdf(), BSDFContext{wl, TransportMode::Radiance}, MediumStack(), false};
        return t.connect(q, smp);
    };
    const ExteriorReflection all(scene, uncut);
    std::vector<double> ratios;
    for (int n = 0; n < 3000; ++n) {
        const SurfaceInteraction xb = receiver(n);
        if (!xb.bsdf() || std::abs(xb.p.y) > 1e-6) continue;
        const ReflectedConnection r = connect(all, xb, n);
        if (r.found) ratios.push_back(r.pdf_bsdf / r.density);
    }
    ASSERT_GT(ratios.size(), 200u);
    std::vector<double> sorted = ratios;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    MneeSettings cut = uncut;
    cut.mis_cutoff = sorted[sorted.size() / 2];
    const ExteriorReflection technique(scene, cut);
    int kept = 0, dropped = 0;
    for (int n = 0; n < 3000; ++n) {
        const SurfaceInteraction xb = receiver(n);
        if (!xb.bsdf() || std::abs(xb.p.y) > 1e-6) continue;
        const ReflectedConnection r = connect(all, xb, n), c = connect(technique, xb, n);
        if (!r.found) {
            EXPECT_FALSE(c.found);
            continue;
        }
        const bool is_cut = r.pdf_bsdf > cut.mis_cutoff * r.density;
        EXPECT_EQ(c.found, !is_cut) << "connect() at ratio " << r.pdf_bsdf / r.density;
        const double d =
            technique.density(xb, *xb.bsdf(), MediumStack(), r.y, *r.light, r.pmf, r.lp.p, r.lp.n, 550, r.pdf_bsdf);
        if (is_cut) {
            EXPECT_EQ(d, 0.0) << "density() at ratio " << r.pdf_bsdf / r.density;
        } else {
            EXPECT_NEAR(d, r.density, 1e-6 * r.density);
            EXPECT_NEAR(c.value[0], r.value[0], 1e-9 * r.value[0]);
        }
        (is_cut ? dropped : kept)++;
    }
    std::cout << "[reflected] cutoff " << cut.mis_cutoff << ": " << kept << " paths kept, " << dropped << " cut\n";
    EXPECT_GT(kept, 100);
    EXPECT_GT(dropped, 100);
}
