// Report building blocks of `snell compare`: colour map, crops and nearest-neighbour enlargement,
// the log-log SVG plot, ordering by PSNR and the JSON/HTML contents.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <regex>

#include "report/compare_report.h"
#include "report/false_colour.h"
#include "report/html_report.h"
#include "report/image_ops.h"
#include "report/svg_plot.h"

using namespace snell;

namespace {
Image ramp(int w, int h) {
    Image img;
    img.width = w;
    img.height = h;
    img.rgb.resize(size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(100 * y + 10 * x + c);
    return img;
}

IntegratorResult result(const std::string& name, double psnr) {
    IntegratorResult r;
    r.name = r.type = name;
    ImageMetrics m;
    m.psnr = psnr;
    m.rel_mse = 0.5;
    r.regions.push_back({"image", Crop{}, m});
    r.convergence.push_back({0.5, 0.5, 4, m});
    r.convergence.push_back({1.0, 1.0, 8, m});
    r.image_png = name + ".png";
    r.error_png = name + "_error.png";
    return r;
}
}  // namespace

TEST(Report, ViridisEndpointsAndClamping) {
    EXPECT_EQ(viridis(0.0), (Rgb8{68, 1, 84}));
    EXPECT_EQ(viridis(1.0), (Rgb8{253, 231, 37}));
    EXPECT_EQ(viridis(0.5), (Rgb8{33, 144, 141}));
    EXPECT_EQ(viridis(-3.0), viridis(0.0));
    EXPECT_EQ(viridis(7.0), viridis(1.0));
    EXPECT_EQ(viridis(std::nan("")), viridis(1.0));
    // Halfway between the first two samples.
    EXPECT_EQ(viridis(1.0 / 16), (Rgb8{70, 23, 103}));
}

TEST(Report, PixelRelativeErrorMatchesRelMseDefinition) {
    Image a = ramp(2, 1), r = ramp(2, 1);
    for (int c = 0; c < 3; ++c) a.at(1, 0, c) = r.at(1, 0, c) + 1.0f;
    EXPECT_DOUBLE_EQ(pixel_relative_error(a, r, 0, 0), 0.0);
    double expect = 0;
    for (int c = 0; c < 3; ++c) expect += 1.0 / (double(r.at(1, 0, c)) * r.at(1, 0, c) + 0.01);
    EXPECT_NEAR(pixel_relative_error(a, r, 1, 0), std::sqrt(expect / 3), 1e-12);
}

TEST(Report, CropAndNearestUpscale) {
    const Image img = ramp(5, 4);
    const Image c = crop_image(img, Crop{1, 2, 3, 2});
    ASSERT_EQ(c.width, 3);
    ASSERT_EQ(c.height, 2);
    EXPECT_EQ(c.at(0, 0, 0), img.at(1, 2, 0));
    EXPECT_EQ(c.at(2, 1, 2), img.at(3, 3, 2));
    EXPECT_THROW(crop_image(img, Crop{3, 0, 3, 1}), std::invalid_argument);
    EXPECT_THROW(crop_image(img, Crop{-1, 0, 1, 1}), std::invalid_argument);

    const Image u = upscale_nearest(c, 3);
    ASSERT_EQ(u.width, 9);
    ASSERT_EQ(u.height, 6);
    for (int y = 0; y < u.height; ++y)
        for (int x = 0; x < u.width; ++x)
            for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(u.at(x, y, ch), c.at(x / 3, y / 3, ch));
    EXPECT_THROW(upscale_nearest(c, 0), std::invalid_argument);

    EXPECT_EQ(enlargement_factor(16, 12), 16);
    EXPECT_EQ(enlargement_factor(64, 48), 4);
    EXPECT_EQ(enlargement_factor(1000, 10), 1);
}

TEST(Report, SvgPlotHasAxesSeriesAndSkipsUnplottablePoints) {
    LogLogPlot p;
    p.title = "t";
    p.x_label = "render time [s]";
    p.y_label = "relMSE <a&b>";
    p.series.push_back({"path", {0.1, 1, 10}, {10, 1, 0.1}});
    p.series.push_back({"nee", {0.1, 0, 1}, {1, 1, -1}});  // only the first point is plottable
    const std::string s = render_svg(p);
    EXPECT_NE(s.find("<svg"), std::string::npos);
    EXPECT_NE(s.find("render time [s]"), std::string::npos);
    EXPECT_NE(s.find("relMSE &lt;a&amp;b&gt;"), std::string::npos);
    std::smatch m;
    const std::regex poly("data-name=\"(\\w+)\"[^>]*points=\"([^\"]*)\"");
    std::vector<std::pair<std::string, int>> found;
    for (auto it = std::sregex_iterator(s.begin(), s.end(), poly); it != std::sregex_iterator(); ++it) {
        const std::string pts = (*it)[2];
        found.push_back({(*it)[1], int(std::count(pts.begin(), pts.end(), ','))});
    }
    ASSERT_EQ(found.size(), 2u);
    EXPECT_EQ(found[0], (std::pair<std::string, int>{"path", 3}));
    EXPECT_EQ(found[1], (std::pair<std::string, int>{"nee", 1}));
    // Ticks at the decades spanned by the data (0.1 .. 10 on both axes).
    EXPECT_NE(s.find(">0.1<"), std::string::npos);
    EXPECT_NE(s.find(">10<"), std::string::npos);
}

TEST(Report, OrderAndJson) {
    CompareReport r;
    r.scene = "s.xml";
    r.width = 4;
    r.height = 3;
    r.reference.source = "file";
    r.reference.file = "ref.exr";
    r.reference.image_png = "reference.png";
    r.integrators = {result("path", 10), result("mnee", std::numeric_limits<double>::infinity()), result("nee", 20)};
    EXPECT_EQ(r.order_by_psnr(), (std::vector<size_t>{1, 2, 0}));
    const nlohmann::json j = report_json(r);
    EXPECT_EQ(j["order_by_psnr"], (nlohmann::json{"mnee", "nee", "path"}));
    EXPECT_EQ(j["integrators"][0]["rank"], 3);
    EXPECT_EQ(j["integrators"][1]["rank"], 1);
    EXPECT_TRUE(j["integrators"][1]["metrics"][0]["psnr"].is_null());  // infinite PSNR
    EXPECT_EQ(j["integrators"][2]["convergence"].size(), 2u);
    EXPECT_EQ(j["reference"]["file"], "ref.exr");
}

// A report on a window of the film (snell compare --reference-offset): crops and region
// rectangles are given back in film coordinates, and the page says where the window is.
TEST(Report, AWindowOfTheFilmIsReportedInFilmCoordinates) {
    CompareReport r;
    r.width = 40;
    r.height = 30;
    r.film_width = 64;
    r.film_height = 48;
    r.window_x = 8;
    r.window_y = 6;
    r.crops = {Crop{12, 14, 16, 12}};
    r.crop_scales = {1};
    r.reference.source = "file";
    r.reference.crop_pngs = {"reference_crop1.png"};
    r.integrators = {result("nee", 20)};
    r.integrators[0].crop_pngs = {"nee_crop1.png"};
    r.integrators[0].regions.push_back({"crop 20,20,16,12", Crop{12, 14, 16, 12}, {}});
    EXPECT_TRUE(r.windowed());
    const nlohmann::json j = report_json(r);
    EXPECT_EQ(j["window"], (nlohmann::json{{"x", 8}, {"y", 6}, {"w", 40}, {"h", 30}}));
    EXPECT_EQ(j["film"]["width"], 64);
    EXPECT_EQ(j["crops"][0]["x"], 20);
    EXPECT_EQ(j["crops"][0]["y"], 20);
    const nlohmann::json& m = j["integrators"][0]["metrics"];
    EXPECT_EQ(m[0]["crop"]["w"], 0);  // the whole window stays Crop{}
    EXPECT_EQ(m.back()["crop"]["x"], 20);
    EXPECT_EQ(m.back()["crop"]["y"], 20);
    const std::string h = html_report(r);
    EXPECT_NE(h.find("window at x=8, y=6 of the 64&times;48 film"), std::string::npos);
    EXPECT_NE(h.find("Crop 1: x=20, y=20"), std::string::npos);
    r.film_width = 40;  // a reference as large as the film: no window
    r.film_height = 30;
    EXPECT_FALSE(r.windowed());
    EXPECT_EQ(html_report(r).find("window at"), std::string::npos);
}

TEST(Report, HtmlHasSectionsInPsnrOrderAndEscapes) {
    CompareReport r;
    r.scene = "<odd>&scene";
    r.width = 4;
    r.height = 3;
    r.reference.source = "file";
    r.reference.file = "ref.exr";
    r.reference.image_png = "reference.png";
    r.integrators = {result("path", 10), result("nee", 20)};
    const std::string h = html_report(r);
    for (const char* id : {"id=\"images\"", "id=\"errors\"", "id=\"metrics\"", "id=\"convergence\"", "<svg"})
        EXPECT_NE(h.find(id), std::string::npos) << id;
    EXPECT_EQ(h.find("<script"), std::string::npos);
    EXPECT_EQ(h.find("http://"), h.find("http://www.w3.org/2000/svg"));  // no external resources
    EXPECT_NE(h.find("&lt;odd&gt;&amp;scene"), std::string::npos);
    EXPECT_EQ(h.find("<odd>"), std::string::npos);
    EXPECT_LT(h.find("src=\"nee.png\""), h.find("src=\"path.png\""));  // best PSNR first
    EXPECT_NE(h.find("image-rendering: pixelated"), std::string::npos);
}
