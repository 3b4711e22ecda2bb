// Props: typed lookups, type errors and unused-parameter reports with file:line.
#include <gtest/gtest.h>

#include "core/props.h"

using namespace snell;

namespace {

SourceLoc at(int line) { return {"scene.xml", line}; }

/// Message of the SceneError thrown by f ("" if none is thrown).
template <typename F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

struct Dummy : Object {};

}  // namespace

TEST(Props, TypedGettersAndDefaults) {
    Props p("bsdf", "dielectric", at(3));
    p.set("flag", true, at(4));
    p.set("count", int64_t(7), at(5));
    p.set("eta", 1.5, at(6));
    p.set("name", std::string("water"), at(7));
    p.set("pos", Vec3(1, 2, 3), at(8));
    p.set("weight", SpectrumData{{}, {0.5}}, at(9));
    EXPECT_TRUE(p.get_bool("flag"));
    EXPECT_DOUBLE_EQ(p.get_float("weight"), 0.5);  // a one-value <spectrum> is a float, as in Mitsuba
    EXPECT_EQ(p.get_int("count"), 7);
    EXPECT_DOUBLE_EQ(p.get_float("eta"), 1.5);
    EXPECT_DOUBLE_EQ(p.get_float("count"), 7.0);  // integers are floats too
    EXPECT_EQ(p.get_string("name"), "water");
    EXPECT_TRUE(p.is_string("name"));
    EXPECT_FALSE(p.is_string("eta"));
    EXPECT_EQ(p.get_vec3("pos").y, 2.0);
    EXPECT_DOUBLE_EQ(p.get_float("missing", 0.25), 0.25);
    EXPECT_EQ(p.get_int("missing2", 3), 3);
    EXPECT_TRUE(p.get_transform("to_world").is_identity());
    EXPECT_NO_THROW(p.check_unused());
}

TEST(Props, WrongTypeNamesParameterLineAndTypes) {
    Props p("shape", "sphere", at(10));
    p.set("radius", std::string("big"), at(12));
    const std::string msg = error_of([&] { p.get_float("radius", 1.0); });
    EXPECT_NE(msg.find("scene.xml:12"), std::string::npos) << msg;
    EXPECT_NE(msg.find("<shape>"), std::string::npos) << msg;
    EXPECT_NE(msg.find("expected float"), std::string::npos) << msg;
    EXPECT_NE(msg.find("got string"), std::string::npos) << msg;
    // A float is not an integer.
    p.set("n", 1.5, at(13));
    EXPECT_NE(error_of([&] { p.get_int("n"); }).find("expected integer, got float"), std::string::npos);
}

TEST(Props, MissingRequiredIsErrorAtElement) {
    Props p("sensor", "perspective", at(20));
    const std::string msg = error_of([&] { p.get_float("fov"); });
    EXPECT_NE(msg.find("scene.xml:20: <sensor>"), std::string::npos) << msg;
    EXPECT_NE(msg.find("fov"), std::string::npos) << msg;
    EXPECT_FALSE(error_of([&] { p.get_string("filename"); }).empty());
    EXPECT_FALSE(error_of([&] { p.get_spectrum("x", SpectrumUse::Reflectance); }).empty());
}

TEST(Props, DuplicateParameterNamesBothPlaces) {
    Props p("bsdf", "diffuse", at(1));
    p.set("reflectance", 0.5, at(2));
    const std::string msg = error_of([&] { p.set("reflectance", 0.7, at(5)); });
    EXPECT_NE(msg.find("scene.xml:5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("scene.xml:2"), std::string::npos) << msg;
}

TEST(Props, Spectra) {
    Props p("bsdf", "x", at(1));
    p.set("c", 0.3, at(2));
    p.set("i", int64_t(2), at(3));
    p.set("one", SpectrumData{{}, {0.7}}, at(4));
    p.set("tab", SpectrumData{{400, 500, 600}, {0.1, 0.2, 0.4}}, at(5));
    p.set("grey", RGB(0.5), at(6));
    p.set("bad", SpectrumData{{500, 400}, {0.1, 0.2}}, at(7));
    const Spectrum c = p.get_spectrum("c", SpectrumUse::Reflectance);
    EXPECT_TRUE(c.is_constant());
    EXPECT_DOUBLE_EQ(c.eval(550), 0.3);
    EXPECT_DOUBLE_EQ(p.get_spectrum("i", SpectrumUse::Unbounded).eval(450), 2.0);
    const Spectrum one = p.get_spectrum("one", SpectrumUse::Reflectance);
    EXPECT_TRUE(one.is_constant());
    EXPECT_DOUBLE_EQ(one.eval(700), 0.7);
    const Spectrum tab = p.get_spectrum("tab", SpectrumUse::Reflectance);
    EXPECT_EQ(tab.kind(), Spectrum::Kind::Tabulated);
    EXPECT_NEAR(tab.eval(450), 0.15, 1e-12);
    EXPECT_NEAR(tab.eval(550), 0.3, 1e-12);
    // RGB goes through the requested upsampling: compare with the factory directly.
    const Spectrum g = p.get_spectrum("grey", SpectrumUse::Reflectance);
    const Spectrum ref = Spectrum::from_rgb_reflectance(RGB(0.5));
    for (double l : {400.0, 550.0, 700.0}) EXPECT_DOUBLE_EQ(g.eval(l), ref.eval(l));
    const std::string msg = error_of([&] { p.get_spectrum("bad", SpectrumUse::Reflectance); });
    EXPECT_NE(msg.find("scene.xml:7"), std::string::npos) << msg;
    // Default when absent.
    EXPECT_DOUBLE_EQ(p.get_spectrum("none", SpectrumUse::Reflectance, Spectrum::constant(0.9)).eval(500), 0.9);
    EXPECT_NO_THROW(p.check_unused());
}

TEST(Props, SpectrumUseSelectsUpsampling) {
    Props p("emitter", "area", at(1));
    p.set("radiance", RGB(1, 0.5, 0.25), at(2));
    const Spectrum s = p.get_spectrum("radiance", SpectrumUse::Illuminant);
    const Spectrum ref = Spectrum::from_rgb_illuminant(RGB(1, 0.5, 0.25));
    for (double l : {420.0, 530.0, 640.0}) EXPECT_DOUBLE_EQ(s.eval(l), ref.eval(l));
}

TEST(Props, GetRgbAcceptsFloat) {
    Props p("emitter", "point", at(1));
    p.set("intensity", 4.0, at(2));
    p.set("color", RGB(1, 2, 3), at(3));
    EXPECT_DOUBLE_EQ(p.get_rgb("intensity", RGB()).g, 4.0);
    EXPECT_DOUBLE_EQ(p.get_rgb("color", RGB()).b, 3.0);
    EXPECT_DOUBLE_EQ(p.get_rgb("none", RGB(0.5)).r, 0.5);
}

TEST(Props, CheckUnusedReportsFirstWithItsLocation) {
    Props p("bsdf", "diffuse", at(1));
    p.set("reflectance", 0.5, at(2));
    p.set("zzz", 1.0, at(3));
    p.set("aaa", 1.0, at(4));  // alphabetically first, but later in the file
    p.get_spectrum("reflectance", SpectrumUse::Reflectance);
    const std::string msg = error_of([&] { p.check_unused(); });
    EXPECT_NE(msg.find("scene.xml:3: <bsdf>: unused parameter 'zzz' for type 'diffuse'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("known parameters: reflectance"), std::string::npos) << msg;
}

TEST(Props, ChildrenAreTrackedAndUnusedChildReported) {
    Props p("shape", "sphere", at(1));
    auto d = std::make_shared<Dummy>();
    p.add_child("", d, at(5));
    EXPECT_NE(error_of([&] { p.check_unused(); }).find("scene.xml:5"), std::string::npos);
    EXPECT_EQ(p.children<Dummy>().size(), 1u);
    EXPECT_EQ(p.child<Dummy>("dummy"), d);
    EXPECT_NO_THROW(p.check_unused());
    p.add_child("", std::make_shared<Dummy>(), at(6));
    EXPECT_NE(error_of([&] { p.child<Dummy>("dummy"); }).find("at most one"), std::string::npos);
}

TEST(Props, RaiseParamUsesParameterLine) {
    Props p("bsdf", "conductor", at(1));
    p.set("material", std::string("unobtainium"), at(9));
    const std::string msg = error_of([&] { p.raise_param("material", "unknown material"); });
    EXPECT_EQ(msg, "scene.xml:9: <bsdf>: unknown material");
    EXPECT_EQ(error_of([&] { p.raise_param("nope", "x"); }), "scene.xml:1: <bsdf>: x");
}
