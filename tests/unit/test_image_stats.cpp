#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/stats_json.h"

using namespace snell;
namespace fs = std::filesystem;

namespace {
// The counters of render/ and geometry/ (not linked here) under the names the report reads,
// and a histogram for the generic "counters" object.
StatCounter g_paths{"render.paths", "camera paths traced"};
StatCounter g_rays{"scene.rays", "closest-hit ray queries"};
StatCounter g_shadow_rays{"scene.shadow_rays", "any-hit ray queries"};
StatCounter g_nan{"render.discarded_nan", "NaN samples"};
StatCounter g_inf{"render.discarded_inf", "infinite samples"};
StatCounter g_negative{"render.discarded_negative", "negative samples"};
StatHistogram g_histogram{"test.histogram", "a histogram", 8};

RenderReport sample_report() {
    RenderReport r;
    r.scene = "scenes/caustic pool/scene.xml";
    r.integrator = "mnee";
    r.width = 640;
    r.height = 360;
    r.spp_requested = 256;
    r.spp_reached = 200;
    r.seconds = 12.5;
    r.threads = 16;
    r.seed = 0xdeadbeefcafeULL;  // above 2^32: must survive as an integer
    reset_stats();
    g_paths += 46080000;
    g_rays += 100000000;
    g_shadow_rays += 25000000;
    g_nan += 3;
    g_inf += 2;
    g_negative += 1;
    g_histogram.add(1, 4);
    g_histogram.add(3);
    r.set_counters(stat_totals());
    r.extra = {{"walks", {{"attempted", 1000}, {"converged", 640}, {"mean_iterations", 4.25}}}};
    r.pixels_dominated = 7;
    r.clamped_share = 0.03;
    r.spread_share = 0.025;
    r.spread_radius = 6;
    r.spread_dropped = 4;
    r.dominated_by_technique = {{"mnee_straight", 5}, {"bsdf_refracted", 2}};
    return r;
}
}  // namespace

TEST(StatsJson, DerivedRates) {
    const RenderReport r = sample_report();
    EXPECT_DOUBLE_EQ(r.paths_per_second(), 46080000 / 12.5);
    EXPECT_DOUBLE_EQ(r.rays_per_second(), 125000000 / 12.5);
    RenderReport z;
    EXPECT_EQ(z.paths_per_second(), 0.0);  // no time measured: no division by zero
    EXPECT_EQ(z.rays_per_second(), 0.0);
}

TEST(StatsJson, FileRoundTrip) {
    const RenderReport r = sample_report();
    const fs::path p = fs::temp_directory_path() / ("snell_stats_" + std::to_string(::getpid()) + ".json");
    write_stats_json(p.string(), r);
    std::ifstream in(p);
    ASSERT_TRUE(in);
    const nlohmann::json j = nlohmann::json::parse(in);
    fs::remove(p);

    EXPECT_EQ(j.at("scene"), r.scene);
    EXPECT_EQ(j.at("integrator"), "mnee");
    EXPECT_EQ(j.at("width"), 640);
    EXPECT_EQ(j.at("height"), 360);
    EXPECT_EQ(j.at("spp_requested"), 256u);
    EXPECT_EQ(j.at("spp_reached"), 200u);
    EXPECT_EQ(j.at("seconds"), 12.5);
    EXPECT_EQ(j.at("threads"), 16);
    EXPECT_EQ(j.at("seed").get<uint64_t>(), 0xdeadbeefcafeULL);
    EXPECT_EQ(j.at("paths"), 46080000u);
    EXPECT_EQ(j.at("rays"), 100000000u);
    EXPECT_EQ(j.at("shadow_rays"), 25000000u);
    EXPECT_DOUBLE_EQ(j.at("paths_per_second").get<double>(), r.paths_per_second());
    EXPECT_DOUBLE_EQ(j.at("rays_per_second").get<double>(), r.rays_per_second());
    EXPECT_EQ(j.at("discarded").at("nan"), 3u);
    EXPECT_EQ(j.at("discarded").at("inf"), 2u);
    EXPECT_EQ(j.at("discarded").at("negative"), 1u);
    EXPECT_EQ(j.at("extra").at("walks").at("converged"), 640);
    EXPECT_EQ(j.at("dominance").at("dominated"), 7u);
    EXPECT_EQ(j.at("dominance").at("by_technique").at("mnee_straight"), 5u);
    EXPECT_EQ(j.at("dominance").at("spread_share"), 0.025);
    EXPECT_EQ(j.at("dominance").at("spread_radius"), 6);
    EXPECT_EQ(j.at("dominance").at("spread_dropped"), 4u);
    // Every registered statistic by name; a histogram without its trailing empty bins.
    EXPECT_EQ(j.at("counters").at("render.paths"), 46080000u);
    EXPECT_EQ(j.at("counters").at("scene.shadow_rays"), 25000000u);
    EXPECT_EQ(j.at("counters").at("test.histogram"), nlohmann::json::array({0, 4, 0, 1}));

    const RenderReport back = j.get<RenderReport>();
    EXPECT_EQ(nlohmann::json(back), j);  // every field survives (rates are re-derived)
}

TEST(StatsJson, FromJsonKeepsDefaultsForMissingKeys) {
    const RenderReport r = nlohmann::json{{"integrator", "path"}, {"width", 8}}.get<RenderReport>();
    EXPECT_EQ(r.integrator, "path");
    EXPECT_EQ(r.width, 8);
    EXPECT_EQ(r.height, 0);
    EXPECT_TRUE(r.extra.is_object());
    EXPECT_TRUE(r.extra.empty());
    EXPECT_TRUE(r.counters.empty());
}

TEST(StatsJson, UnwritablePathThrowsWithPath) {
    const std::string p = "/nonexistent_snell_dir/stats.json";
    try {
        write_stats_json(p, sample_report());
        FAIL() << "expected an exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
}
