#include <gtest/gtest.h>

#include <regex>

#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/html_page.hpp"
#include "cropsight/report/sequence_page.hpp"
#include "cropsight/report/sequence_summary.hpp"
#include "cropsight/report/svg_plot.hpp"
#include "io/sequence_fixture.hpp"
#include "testing/testing.hpp"

namespace cropsight::report {
namespace {

using namespace cropsight::testing;

TEST(HtmlPage, Base64KnownVectors) {
  // RFC 4648 section 10.
  EXPECT_EQ(base64_encode(""), "");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("foo"), "Zm9v");
  EXPECT_EQ(base64_encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64_encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64_encode(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(HtmlPage, EscapesText) {
  EXPECT_EQ(html_escape("<a href=\"x\">&'"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;");
  HtmlPage page("T<1>");
  page.section("S&S");
  page.table({"a"}, {{"<script>"}});
  const std::string h = page.html();
  EXPECT_EQ(h.find("<script>"), std::string::npos);
  EXPECT_NE(h.find("&lt;script&gt;"), std::string::npos);
  EXPECT_NE(h.find("<title>T&lt;1&gt;</title>"), std::string::npos);
}

// Result sections come before data sections whatever order they were added in, and every
// section stays closed where it was opened.
TEST(HtmlPage, ResultPartComesBeforeDataPart) {
  HtmlPage page("parts");
  page.section("Data one", HtmlPage::Part::Data);
  page.paragraph("data text");
  page.section("Result one");
  page.paragraph("result text");
  page.section("Data two", HtmlPage::Part::Data);
  page.section("Result two", HtmlPage::Part::Result);  // left open: html() closes it
  const std::string h = page.html();
  const auto at = [&](const std::string& s) {
    const auto p = h.find(s);
    EXPECT_NE(p, std::string::npos) << s;
    return p;
  };
  EXPECT_LT(at("<h2>Result one</h2>"), at("<p>result text</p>"));
  EXPECT_LT(at("<p>result text</p>"), at("<h2>Result two</h2>"));
  EXPECT_LT(at("<h2>Result two</h2>"), at("<h2>Data one</h2>"));
  EXPECT_LT(at("<h2>Data one</h2>"), at("<p>data text</p>"));
  EXPECT_LT(at("<p>data text</p>"), at("<h2>Data two</h2>"));
  std::size_t open = 0, close = 0;
  for (std::size_t p = h.find("<section>"); p != std::string::npos; p = h.find("<section>", p + 1)) ++open;
  for (std::size_t p = h.find("</section>"); p != std::string::npos; p = h.find("</section>", p + 1)) ++close;
  EXPECT_EQ(open, 4u);
  EXPECT_EQ(close, 4u);
  // The open result section is closed before the data part starts (no nesting across parts).
  EXPECT_NE(h.find("</section>\n<section>\n<h2>Data one"), std::string::npos) << h;
}

TEST(HtmlPage, EvenlySpacedFrames) {
  EXPECT_EQ(evenly_spaced_frames(30, 4), (std::vector<int>{0, 10, 19, 29}));
  EXPECT_EQ(evenly_spaced_frames(3, 5), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(evenly_spaced_frames(1, 4), (std::vector<int>{0}));
  EXPECT_EQ(evenly_spaced_frames(10, 1), (std::vector<int>{0}));
  EXPECT_TRUE(evenly_spaced_frames(0, 3).empty());
}

TEST(HtmlPage, SvgPlotHasOnePolylinePerSeries) {
  const std::string s = svg_line_plot({{"a", {0, 1, 2}, {1, 2, 3}}, {"b", {0, 1}, {0, NAN}}}, {"t", "x", "y"});
  EXPECT_EQ(s.rfind("<svg", 0), 0u);
  std::size_t n = 0;
  for (std::size_t p = s.find("<polyline"); p != std::string::npos; p = s.find("<polyline", p + 1)) ++n;
  EXPECT_EQ(n, 2u);
}

TEST(SequenceSummary, MatchesAHandCount) {
  TempDir tmp;
  write_fixture_sequence(tmp / "seq", 3);
  const io::SequenceReader reader(tmp / "seq");
  const SequenceSummary s = summarize_sequence(reader);
  double valid = 0, labelled = 0;
  for (int i = 0; i < 3; ++i) {
    const RgbdFrame f = fixture_frame(i, fixture_camera());
    int nv = 0, nl = 0;
    for (auto d : f.depth.data) nv += d != 0;
    for (auto l : f.labels.data) nl += l != 0;
    valid += nv / double(f.depth.size()) / 3.0;
    labelled += nl / double(f.depth.size()) / 3.0;
  }
  EXPECT_NEAR(s.valid_depth_fraction, valid, 1e-12);
  EXPECT_LT(s.valid_depth_fraction, 1.0);
  EXPECT_NEAR(s.labelled_fraction, labelled, 1e-12);
  EXPECT_EQ(s.instances, 2);
  EXPECT_EQ(s.visible_instances_per_frame, (std::vector<int>{2, 2, 2}));
  EXPECT_EQ(s.valid_depth_per_frame.size(), 3u);
  EXPECT_NEAR(s.depth_min_m, 1.201, 1e-9);  // the smallest non-hole depth in the fixture
}

TEST(SequencePage, IsSelfContained) {
  TempDir tmp;
  write_fixture_sequence(tmp / "seq", 5);
  const io::SequenceReader reader(tmp / "seq");
  HtmlPage page("fixture");
  add_sequence_sections(page, reader, summarize_sequence(reader), {});
  page.write(tmp / "page.html");
  const std::string h = io::read_file(tmp / "page.html");
  // 4 frames shown x (depth, colour, labels) embedded PNGs; nothing loaded from elsewhere.
  std::size_t imgs = 0;
  for (std::size_t p = h.find("src=\"data:image/png;base64,"); p != std::string::npos;
       p = h.find("src=\"data:image/png;base64,", p + 1))
    ++imgs;
  EXPECT_EQ(imgs, 12u);
  EXPECT_FALSE(std::regex_search(h, std::regex("(src|href)=\"(https?:|//|[a-zA-Z0-9_./-]+\\.(png|css|js))")));
  EXPECT_EQ(h.find("<script"), std::string::npos);
  EXPECT_NE(h.find("ground-truth instances"), std::string::npos);
  EXPECT_NE(h.find("<svg"), std::string::npos);
}

}  // namespace
}  // namespace cropsight::report
