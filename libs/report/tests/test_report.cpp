// The report library against independent oracles: RFC 4648's base64 test vectors, an XML parser
// (Python's, Debian's /usr/bin/python3) on the SVG, tick placement and axis scales by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include "roadslam/report/html_page.h"
#include "roadslam/report/svg_plot.h"

using namespace roadslam::report;
namespace fs = std::filesystem;

TEST(Report, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(Report, EscapesMarkup) {
  EXPECT_EQ(htmlEscape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
}

TEST(Report, NiceTicksAreRoundAndCoverTheRange) {
  const auto t = niceTicks(0.0, 1.0, 5);
  ASSERT_EQ(t.size(), 6u);
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(t[i], 0.2 * i, 1e-12);
  const auto u = niceTicks(13.0, 87.0, 6);
  EXPECT_NEAR(u.front(), 20.0, 1e-12);
  EXPECT_NEAR(u.back(), 80.0, 1e-12);
  EXPECT_NEAR(u[1] - u[0], 20.0, 1e-12) << "74 / 6 = 12.3 rounds up to a step of 20";
}

TEST(Report, SvgPlotIsWellFormedXmlWithOneMarkPerFinitePoint) {
  Series a{"rte <%>", {0, 1, 2, 3}, {1.0, 0.5, std::nan(""), 0.25}};
  Series b{"b", {0, 3}, {2.0, 2.0}};
  PlotOptions o;
  o.title = "RTE & voxel";
  o.x_markers = {1.5};
  const std::string svg = svgPlot({a, b}, o);
  const fs::path p = fs::temp_directory_path() / "roadslam_test_report.svg";
  std::ofstream(p) << svg;
  const std::string cmd = "/usr/bin/python3 -c \"import sys, xml.dom.minidom as m; d = m.parse(sys.argv[1]); "
                          "print(len(d.getElementsByTagName('circle')))\" " + p.string() + " > " + p.string() + ".n";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "not well-formed XML:\n" << svg;
  std::ifstream n(p.string() + ".n");
  int circles = -1;
  n >> circles;
  EXPECT_EQ(circles, 5) << "3 finite points of a, 2 of b";
  EXPECT_NE(svg.find("RTE &amp; voxel"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos) << "the marker";
  EXPECT_NE(svgPlot({}, o).find("no data"), std::string::npos);
}

TEST(Report, PageEmbedsPicturesAndNeedsNoNetwork) {
  const fs::path png = fs::temp_directory_path() / "roadslam_test_report.png";
  std::ofstream(png, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8);
  HtmlPage page("Title <1>");
  page.table({"a", "b"}, {{"1", "x<y"}, {"2", "z"}}, {1});
  page.pngFile(png.string(), "pic");
  const std::string html = page.str();
  EXPECT_NE(html.find("<title>Title &lt;1&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64," + base64(std::string("\x89PNG\r\n\x1a\n", 8))), std::string::npos);
  EXPECT_NE(html.find("<tr class=\"best\"><td>2</td>"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos) << "nothing fetched from elsewhere";
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_THROW(page.pngFile("/nonexistent.png", "x"), std::runtime_error);
}

namespace {
/// Centres of the <circle> marks in order.
std::vector<std::pair<double, double>> circles(const std::string& svg) {
  std::vector<std::pair<double, double>> out;
  const std::regex re("<circle cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    out.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  return out;
}
}  // namespace

TEST(Report, EqualAxesDrawAMetreAsLongOnXAsOnY) {
  Series path{"path", {0, 10, 10}, {0, 0, 1}};  // 10 m east, then 1 m north
  PlotOptions o;
  o.equal_axes = true;
  const auto c = circles(svgPlot({path}, o));
  ASSERT_EQ(c.size(), 3u);
  const double px_per_m_x = std::abs(c[1].first - c[0].first) / 10, px_per_m_y = std::abs(c[2].second - c[1].second) / 1;
  EXPECT_NEAR(px_per_m_x, px_per_m_y, 0.02 * px_per_m_x);
  EXPECT_LT(c[2].second, c[1].second) << "north is up";
  o.equal_axes = false;
  const auto d = circles(svgPlot({path}, o));
  EXPECT_GT(std::abs(d[2].second - d[1].second) / 1, 3 * std::abs(d[1].first - d[0].first) / 10) << "stretched without";
}

TEST(Report, YIncludeZeroPutsZeroOnTheAxis) {
  PlotOptions o;
  o.y_include_zero = true;
  const std::string svg = svgPlot({{"rate", {0, 1, 2}, {753, 754, 753}}}, o);
  EXPECT_NE(svg.find("text-anchor=\"end\">0</text>"), std::string::npos) << "a 0 tick on the y axis";
  o.y_include_zero = false;
  EXPECT_EQ(svgPlot({{"rate", {0, 1, 2}, {753, 754, 753}}}, o).find("text-anchor=\"end\">0</text>"), std::string::npos);
}
