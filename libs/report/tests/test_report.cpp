// The report library against independent oracles: RFC 4648's base64 test vectors, an XML parser
// (Python's, Debian's /usr/bin/python3) on the SVG, and tick placement by hand.
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
