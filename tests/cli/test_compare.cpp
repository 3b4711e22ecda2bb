// End-to-end checks of `snell compare` (two ctest entries, see cmake/module_app.cmake):
//   CompareCli.*  runs a small comparison into SNELL_COMPARE_DIR, checks report.json against the
//                 images it names, and checks the error messages;
//   CompareHtml.* loads that folder's report.html in headless Chromium and checks the DOM.
// Environment: SNELL_BIN (the snell executable), SNELL_COMPARE_DIR (report folder).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "io/image.h"
#include "report/image_metrics.h"
#include "report/image_ops.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace snell;

namespace {

std::string env(const char* name) {
    const char* v = std::getenv(name);
    if (!v || !*v) throw std::runtime_error(std::string("environment variable ") + name + " is not set");
    return v;
}

struct CommandResult {
    int status = -1;
    std::string output;  ///< stdout and stderr
};

CommandResult run(const std::string& cmd) {
    CommandResult r;
    FILE* p = popen((cmd + " 2>&1").c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
    const int st = pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

const char* k_integrators[] = {"pt", "nee", "mnee"};
constexpr int k_steps = 2;

// The comparison every check below reads: 64x48 droplet, 0.5 s per integrator, two threads.
std::string compare_command(const std::string& dir) {
    return quote(env("SNELL_BIN")) + " compare builtin:droplet --integrators pt,nee,mnee --time 0.5 -t 2 --seed 7" +
           " -D res_x=64 -D res_y=48 --reference-integrator mnee --reference-spp 64 --crop 20,20,16,12" +
           " --convergence-steps " + std::to_string(k_steps) + " -q --out " + quote(dir);
}

}  // namespace

TEST(CompareCli, ReportJsonHasEveryNumberAndMatchesTheImages) {
    const fs::path dir = env("SNELL_COMPARE_DIR");
    fs::remove_all(dir);
    const CommandResult r = run(compare_command(dir.string()));
    ASSERT_EQ(r.status, 0) << r.output;

    std::ifstream in(dir / "report.json");
    ASSERT_TRUE(in) << "no report.json in " << dir;
    const json j = json::parse(in);
    EXPECT_EQ(j["scene"], "builtin:droplet");
    EXPECT_EQ(j["width"], 64);
    EXPECT_EQ(j["height"], 48);
    EXPECT_EQ(j["time_budget"], 0.5);
    EXPECT_EQ(j["threads"], 2);
    EXPECT_EQ(j["seed"], 7);
    ASSERT_EQ(j["crops"].size(), 1u);
    EXPECT_EQ(j["crops"][0]["w"], 16);

    const json& ref = j["reference"];
    EXPECT_EQ(ref["source"], "render");
    EXPECT_EQ(ref["integrator"], "mnee");
    EXPECT_EQ(ref["spp"], 64);
    EXPECT_EQ(ref["stats"]["spp_reached"], 64);
    const Image ref_img = read_exr((dir / ref["image_exr"].get<std::string>()).string());
    ASSERT_TRUE(fs::exists(dir / ref["image_png"].get<std::string>()));
    ASSERT_EQ(ref["crop_pngs"].size(), 1u);
    EXPECT_TRUE(fs::exists(dir / ref["crop_pngs"][0].get<std::string>()));

    ASSERT_EQ(j["integrators"].size(), 3u);
    std::set<int> ranks;
    for (size_t i = 0; i < 3; ++i) {
        const json& it = j["integrators"][i];
        SCOPED_TRACE(k_integrators[i]);
        EXPECT_EQ(it["name"], k_integrators[i]);
        EXPECT_EQ(it["stats"]["time_limit"], 0.5);
        EXPECT_EQ(it["stats"]["threads"], 2);
        EXPECT_GT(it["spp_reached"].get<int>(), 0);
        EXPECT_GT(it["paths_per_second"].get<double>(), 0);
        ranks.insert(it["rank"].get<int>());

        // Metrics recomputed from the written EXRs agree with the JSON.
        const Image img = read_exr((dir / it["image_exr"].get<std::string>()).string());
        ASSERT_EQ(it["metrics"].size(), 2u);  // whole image and the crop
        const Crop crops[2] = {Crop{}, Crop{20, 20, 16, 12}};
        for (int g = 0; g < 2; ++g) {
            const json& m = it["metrics"][g];
            const ImageMetrics expect = compare_images(img, ref_img, crops[g]);
            EXPECT_NEAR(m["rel_mse"].get<double>(), expect.rel_mse, 1e-9 * expect.rel_mse);
            EXPECT_NEAR(m["rmse"].get<double>(), expect.rmse, 1e-9 * expect.rmse);
            EXPECT_NEAR(m["psnr"].get<double>(), expect.psnr, 1e-9 * std::abs(expect.psnr));
            EXPECT_NEAR(m["smape"].get<double>(), expect.smape, 1e-9 * expect.smape);
        }
        EXPECT_EQ(it["metrics"][1]["region"], "crop 20,20,16,12");

        // Convergence: budget/4, budget/2, budget; the last point is the equal-time render.
        const json& conv = it["convergence"];
        ASSERT_EQ(conv.size(), size_t(k_steps + 1));
        for (int k = 0; k <= k_steps; ++k)
            EXPECT_DOUBLE_EQ(conv[k]["time_limit"].get<double>(), 0.5 / std::exp2(k_steps - k));
        EXPECT_EQ(conv[k_steps]["rel_mse"], it["metrics"][0]["rel_mse"]);

        for (const char* key : {"image_png", "error_png"})
            EXPECT_TRUE(fs::exists(dir / it[key].get<std::string>())) << key;
        EXPECT_TRUE(fs::exists(dir / it["crop_pngs"][0].get<std::string>()));
        // Walk statistics exactly where manifold walks happen.
        EXPECT_EQ(it.contains("mnee"), std::string(k_integrators[i]) == "mnee");
    }
    EXPECT_GT(j["integrators"][2]["mnee"]["walks_started"].get<double>(), 0);
    EXPECT_EQ(ranks, (std::set<int>{1, 2, 3}));
    // order_by_psnr is sorted by whole-image PSNR.
    double last = INFINITY;
    for (const auto& name : j["order_by_psnr"])
        for (const auto& it : j["integrators"])
            if (it["name"] == name) {
                EXPECT_LE(it["metrics"][0]["psnr"].get<double>(), last);
                last = it["metrics"][0]["psnr"].get<double>();
            }
    EXPECT_TRUE(fs::exists(dir / "report.html"));
}

TEST(CompareCli, ErrorsAreClearAndExitNonZero) {
    const std::string snell = quote(env("SNELL_BIN"));
    const fs::path dir = env("SNELL_COMPARE_DIR");
    const std::string base = snell + " compare builtin:droplet --time 0.1 -D res_x=64 -D res_y=48 -q ";
    const fs::path scratch = dir.string() + "_errors";
    struct Case {
        std::string args, expect;
    } cases[] = {
        {"--integrators path,foo --reference-spp 1", "unknown integrator 'foo'"},
        {"--integrators path --reference /nonexistent/ref.exr", "/nonexistent/ref.exr"},
        {"--integrators path", "compare needs a reference"},
        {"--integrators path --reference-spp 1 --crop 60,40,8,8", "outside the 64x48 image"},
        {"--integrators path --reference-spp 1 -D integrator=nee", "conflicts with --integrators"},
    };
    for (const Case& c : cases) {
        const CommandResult r = run(base + c.args + " --out " + quote(scratch.string()));
        EXPECT_NE(r.status, 0) << c.args;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    }
    // A reference of another size (the 64x48 one from the first test against a 32x24 render).
    const fs::path ref = dir / "reference.exr";
    if (fs::exists(ref)) {
        const CommandResult r =
            run(snell + " compare builtin:droplet --time 0.1 -D res_x=32 -D res_y=24 -q --integrators path" +
                " --reference " + quote(ref.string()) + " --out " + quote(scratch.string()));
        EXPECT_NE(r.status, 0);
        EXPECT_NE(r.output.find("reference is 64x48 but the scene renders 32x24"), std::string::npos) << r.output;
    }
    fs::remove_all(scratch);
}

// `mnee-paper` is the paper's estimator (solutions=one: the straight seed alone, no surface
// trials), beside the default `mnee` (which walks surface seeds), in one comparison.
TEST(CompareCli, MneePaperIsThePapersEstimator) {
    const std::string snell = quote(env("SNELL_BIN"));
    const fs::path out = env("SNELL_COMPARE_DIR") + std::string("_paper");
    fs::remove_all(out);
    const CommandResult r = run(snell + " compare builtin:droplet --integrators mnee,mnee-paper --time 0.3 -t 2" +
                                " --seed 3 -D res_x=32 -D res_y=24 --reference-spp 2 --convergence-steps 0 -q" +
                                " --out " + quote(out.string()));
    ASSERT_EQ(r.status, 0) << r.output;
    std::ifstream in(out / "report.json");
    const json j = json::parse(in);
    ASSERT_EQ(j["integrators"].size(), 2u);
    const auto surface_seeds = [](const json& it) {
        double n = 0;
        for (const auto& kv : it["mnee"]["surface_seeds"].items()) n += kv.value().get<double>();
        return n;
    };
    for (const json& it : j["integrators"]) {
        SCOPED_TRACE(it["name"].get<std::string>());
        EXPECT_EQ(it["type"], "mnee");
        EXPECT_GT(it["mnee"]["walks_started"].get<double>(), 0);
        if (it["name"] == "mnee-paper") {
            EXPECT_EQ(surface_seeds(it), 0);
            EXPECT_EQ(it["mnee"]["trials_per_solution"]["estimates"].get<double>(), 0);
        } else {
            EXPECT_GT(surface_seeds(it), 0);
        }
    }
    fs::remove_all(out);
}

// A reference rendered on a crop of the film (--reference-offset): every image, metric and crop of
// the report covers that window, crops are named in film coordinates, and the whole film is kept.
TEST(CompareCli, AReferenceWindowScoresEveryImageThere) {
    const std::string snell = quote(env("SNELL_BIN"));
    const fs::path dir = env("SNELL_COMPARE_DIR");
    const fs::path full_ref = dir / "reference.exr";
    ASSERT_TRUE(fs::exists(full_ref)) << "needs the reference of ReportJsonHasEveryNumberAndMatchesTheImages";
    const fs::path scratch = dir.string() + "_window";
    fs::remove_all(scratch);
    fs::create_directories(scratch);
    const Crop window{8, 6, 40, 30};
    const Image ref_window = crop_image(read_exr(full_ref.string()), window);
    const fs::path ref = scratch / "window_ref.exr";
    write_exr(ref.string(), ref_window);
    const fs::path out = scratch / "report";
    const CommandResult r =
        run(snell + " compare builtin:droplet --integrators nee --time 0.2 -t 2 --seed 7 -D res_x=64 -D res_y=48" +
            " --reference " + quote(ref.string()) + " --reference-offset 8,6 --crop 20,20,16,12" +
            " --convergence-steps 1 -q --out " + quote(out.string()));
    ASSERT_EQ(r.status, 0) << r.output;
    std::ifstream in(out / "report.json");
    const json j = json::parse(in);
    EXPECT_EQ(j["width"], 40);
    EXPECT_EQ(j["height"], 30);
    EXPECT_EQ(j["window"], (json{{"x", 8}, {"y", 6}, {"w", 40}, {"h", 30}}));
    EXPECT_EQ(j["film"]["width"], 64);
    EXPECT_EQ(j["crops"][0]["x"], 20);  // film coordinates, as given
    const json& it = j["integrators"][0];
    const Image img = read_exr((out / it["image_exr"].get<std::string>()).string());
    ASSERT_EQ(img.width, 40);
    ASSERT_EQ(img.height, 30);
    // The report's image is exactly the film's window.
    const Image film = read_exr((out / "nee_film.exr").string());
    ASSERT_EQ(film.width, 64);
    EXPECT_EQ(crop_image(film, window).rgb, img.rgb);
    EXPECT_EQ(it["metrics"][1]["region"], "crop 20,20,16,12");
    EXPECT_EQ(it["metrics"][1]["crop"]["x"], 20);          // film coordinates, like the region's name
    const Crop crops[2] = {Crop{}, Crop{12, 14, 16, 12}};  // the crop in the window's coordinates
    for (int g = 0; g < 2; ++g) {
        const ImageMetrics expect = compare_images(img, ref_window, crops[g]);
        EXPECT_NEAR(it["metrics"][g]["rel_mse"].get<double>(), expect.rel_mse, 1e-9 * expect.rel_mse);
    }
    EXPECT_EQ(it["convergence"].back()["rel_mse"], it["metrics"][0]["rel_mse"]);
    // Errors: a window that does not fit, a crop outside it, an offset without a reference file.
    const std::string base = snell + " compare builtin:droplet --integrators nee --time 0.1 -D res_x=64 -D res_y=48 -q";
    struct Case {
        std::string args, expect;
    } cases[] = {
        {" --reference " + quote(ref.string()) + " --reference-offset 30,20", "does not fit inside the 64x48 film"},
        {" --reference " + quote(ref.string()) + " --reference-offset 8,6 --crop 0,0,4,4",
         "outside the 40x30 reference window at 8,6 of the film"},
        {" --reference-spp 1 --reference-offset 8,6", "--reference-offset requires --reference"},
        {" --reference " + quote(ref.string()) + " --reference-offset 8", "--reference-offset must be x,y"},
    };
    for (const Case& c : cases) {
        const CommandResult e = run(base + c.args + " --out " + quote((scratch / "err").string()));
        EXPECT_NE(e.status, 0) << c.args;
        EXPECT_NE(e.output.find(c.expect), std::string::npos) << c.args << "\n" << e.output;
    }
    fs::remove_all(scratch);
}

// The page opens from disk in a real browser, and its DOM holds the metrics table and images
// whose files exist beside it.
TEST(CompareHtml, ChromiumFindsTableAndImages) {
    const fs::path dir = env("SNELL_COMPARE_DIR");
    const fs::path page = fs::absolute(dir / "report.html");
    ASSERT_TRUE(fs::exists(page)) << page << " missing: run the cli.compare test first";
    if (run("command -v chromium").status != 0)
        FAIL() << "chromium is not installed: the report page test needs Debian's chromium package "
                  "(scripts/install-deps.sh installs it)";
    const fs::path profile = dir.string() + "_chromium_profile";
    fs::remove_all(profile);
    const CommandResult r =
        run("timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-background-networking "
            "--disable-component-update --disable-sync --no-first-run --user-data-dir=" +
            quote(profile.string()) + " --dump-dom " + quote("file://" + page.string()) + " 2>/dev/null");
    fs::remove_all(profile);
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string& dom = r.output;
    ASSERT_NE(dom.find("<table id=\"metrics\">"), std::string::npos) << dom.substr(0, 2000);

    // One metrics row per integrator and region (3 integrators x (image + 1 crop)).
    const size_t t0 = dom.find("<table id=\"metrics\">"), t1 = dom.find("</table>", t0);
    const std::string table = dom.substr(t0, t1 - t0);
    const std::regex row("<tr[ >]");
    EXPECT_EQ(std::distance(std::sregex_iterator(table.begin(), table.end(), row), std::sregex_iterator()), 1 + 3 * 2);
    for (const char* name : k_integrators)
        EXPECT_NE(table.find(std::string(">") + name + "<"), std::string::npos) << name;

    // Images: reference + 3 renders, (1 + 3) crops, 3 error maps; every file exists.
    const std::regex img("<img [^>]*src=\"([^\"]+)\"");
    int count = 0;
    for (auto it = std::sregex_iterator(dom.begin(), dom.end(), img); it != std::sregex_iterator(); ++it) {
        ++count;
        const std::string src = (*it)[1];
        EXPECT_TRUE(fs::exists(dir / src)) << src;
    }
    EXPECT_EQ(count, 4 + 4 + 3);
    EXPECT_NE(dom.find("<svg"), std::string::npos);
    EXPECT_NE(dom.find("class=\"series\""), std::string::npos);
}
