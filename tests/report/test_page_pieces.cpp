// The demo page's building blocks: chapters in HtmlPage, the SVG overlay, orthographic cloud
// pictures and the image helpers (crop, side by side, disparity colours).
#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/report/cloud_view.hpp"
#include "cropsight/report/html_page.hpp"
#include "cropsight/report/render.hpp"
#include "cropsight/report/svg_overlay.hpp"

using namespace cropsight;
using namespace cropsight::report;

namespace {

int count_in(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(PagePieces, ChaptersKeepEachSystemsResultsBeforeItsDataAndListThemOnTop) {
  HtmlPage page("demo");
  page.paragraph("opening words");
  page.chapter("First system", "first");
  page.section("its data", HtmlPage::Part::Data);
  page.paragraph("data one");
  page.section("its result");
  page.paragraph("result one");
  page.chapter("Second system", "second");
  page.paragraph("result two");
  const std::string html = page.html();
  EXPECT_LT(html.find("href=\"#first\""), html.find("href=\"#second\""));
  EXPECT_LT(html.find("opening words"), html.find("<article class=\"system\" id=\"first\">"));
  EXPECT_LT(html.find("result one"), html.find("data one"));
  EXPECT_LT(html.find("data one"), html.find("<article class=\"system\" id=\"second\">"));
  EXPECT_LT(html.find("id=\"second\""), html.find("result two"));
  EXPECT_NE(html.find("<h3>its result</h3>"), std::string::npos);  // a level below the chapter's <h2>
  EXPECT_EQ(count_in(html, "<article"), count_in(html, "</article>"));
  EXPECT_EQ(count_in(html, "<section>"), count_in(html, "</section>"));
  EXPECT_THROW(page.chapter("x", "not an id"), Error);
  EXPECT_THROW(page.chapter("x", "first"), Error);
}

TEST(PagePieces, OverlayEmbedsTheImageAndDrawsEscapedMarksInItsPixels) {
  SvgOverlay o(ColorImage(40, 30, {10, 20, 30}), 80);
  o.rect(1, 2, 11, 12, "#2a7");
  o.line(0, 0, 40, 30, "red");
  o.circle(20, 15, 4, "blue");
  o.cross(5, 5, 3, "white");
  o.text(2, 28, "<b> & co", "white");
  const std::string svg = o.svg();
  EXPECT_NE(svg.find("viewBox=\"0 0 40 30\""), std::string::npos);
  EXPECT_NE(svg.find("width=\"80\" height=\"60\""), std::string::npos);
  EXPECT_NE(svg.find("href=\"data:image/png;base64,"), std::string::npos);
  EXPECT_EQ(count_in(svg, "<line"), 3);  // the line and the cross's two strokes
  EXPECT_NE(svg.find("&lt;b&gt; &amp; co"), std::string::npos);
  EXPECT_EQ(svg.find("<b>"), std::string::npos);
}

TEST(PagePieces, CloudViewFramesThePointsAndDrawsTheNearestOnTop) {
  const std::vector<Eigen::Vector3f> pts = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
  const CloudView v = fit_cloud_view(pts, Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY(), 100, 0.f);
  EXPECT_NEAR(v.pixel({0, 2, 0}).x(), 0.f, 1e-4f);
  EXPECT_NEAR(v.pixel({0, 2, 0}).y(), 0.f, 1e-4f);  // the highest point at the top
  EXPECT_NEAR(v.pixel({1, 0, 0}).x(), 100.f, 1e-3f);
  EXPECT_EQ(v.height, 200);
  Cloud c;
  c.points = {{0.5f, 1, 0.f}, {0.5f, 1, 1.f}, {0.5f, 1, -1.f}};  // one pixel, three depths
  const ColorImage img = render_cloud(c, {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}}, v, 3);
  EXPECT_EQ(img.at(50, 100), (Rgb8{0, 255, 0}));  // z = 1 is nearest to a viewer looking along -z
  EXPECT_EQ(img.at(5, 5), (Rgb8{255, 255, 255}));
  EXPECT_THROW(render_cloud(c, {{0, 0, 0}}, v, 3), Error);
  EXPECT_THROW(fit_cloud_view({}, Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY(), 100), Error);
}

TEST(PagePieces, ImageHelpersPlaceCropAndColour) {
  const ColorImage a(4, 3, {255, 0, 0}), b(2, 5, {0, 0, 255});
  const ColorImage both = side_by_side({a, b}, 2, {9, 9, 9});
  EXPECT_EQ(both.width, 8);
  EXPECT_EQ(both.height, 5);
  EXPECT_EQ(both.at(3, 0), (Rgb8{255, 0, 0}));
  EXPECT_EQ(both.at(4, 0), (Rgb8{9, 9, 9}));
  EXPECT_EQ(both.at(6, 4), (Rgb8{0, 0, 255}));
  EXPECT_EQ(both.at(0, 4), (Rgb8{9, 9, 9}));
  ColorImage grad(10, 1);
  for (int u = 0; u < 10; ++u) grad.at(u, 0) = {std::uint8_t(u), 0, 0};
  const ColorImage part = crop(grad, 8, 0, 4, 1);  // moved inside the image
  EXPECT_EQ(part.width, 4);
  EXPECT_EQ(part.at(0, 0).r, 6);
  DepthImage disp(3, 1);
  disp.data = {0, 256 * 5, 256 * 50};
  const ColorImage dc = disparity_colormap(disp);
  EXPECT_EQ(dc.at(0, 0), (Rgb8{0, 0, 0}));
  EXPECT_GT(int(dc.at(2, 0).r), int(dc.at(2, 0).b));  // large disparity, near: red
  EXPECT_GT(int(dc.at(1, 0).b), int(dc.at(1, 0).r));
}
