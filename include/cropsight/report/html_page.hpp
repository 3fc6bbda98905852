#pragma once
// HtmlPage: builds ONE self-contained HTML file (inline CSS, images as base64 PNG data URIs,
// inline SVG; nothing fetched from the network), so a report can be mailed or opened offline.
//
//   HtmlPage page("Sequence uk-seq");
//   page.section("Summary");
//   page.table({"field", "value"}, {{"frames", "30"}});
//   page.figures({{depth_png, "depth 0"}, {color_png, "colour 0"}});
//   page.svg(svg_line_plot(...));
//   page.write("page.html");   // atomic
//
// All text arguments are HTML-escaped; only raw_html() and svg() insert markup as given.
//
// A page has two parts: results first, then the data they were computed from. A section opened
// with Part::Data (the sequence summary, camera, frames, ground truth) is shown after every
// Part::Result section, whatever order the sections were added in, so a page opens with what was
// found (detections, map, sizes, timing) and not with a table of metadata.
//
// A page about several systems (the demo page) opens a chapter per system: chapter() starts an
// <article> with an <h2> and a link in the page's table of contents; the sections that follow
// belong to it (their headings one level lower), and the result-before-data rule holds within
// each chapter, so one system's data never lands below another system's results.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cropsight/core/image.hpp"

namespace cropsight::report {

/// One image of a row of figures, with its caption.
struct Figure {
  std::string png;        ///< PNG file bytes (io::encode_png)
  std::string caption;    ///< plain text
  int display_width = 0;  ///< CSS pixels; 0 = natural width
};
/// Figure from an image (encoded as PNG).
Figure make_figure(const ColorImage& image, std::string caption, int display_width = 0);

class HtmlPage {
 public:
  /// Where a section is shown: every Result section comes before every Data section.
  enum class Part { Result, Data };

  explicit HtmlPage(std::string title);

  /// Starts a new <section> with an <h2> heading (closing the previous one) in `part`; what is
  /// added next (headings, tables, figures, ...) belongs to it. Content added before the first
  /// section belongs to the result part.
  void section(const std::string& heading, Part part = Part::Result);
  /// Starts a chapter (closing the previous one): an <article id="`id`"> headed by an <h2>,
  /// listed in the table of contents shown under the title. `id` must be a valid HTML id
  /// (letters, digits, '-'); Error("chapter", ...) otherwise, or when it repeats.
  void chapter(const std::string& heading, const std::string& id);
  void heading(const std::string& text, int level = 3);
  void paragraph(const std::string& text);
  /// A table; every row should have header.size() cells. Cells are plain text.
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
             const std::string& caption = "");
  /// Two-column field/value table.
  void key_values(const std::vector<std::pair<std::string, std::string>>& rows, const std::string& caption = "");
  /// A row of images (wraps on narrow screens).
  void figures(const std::vector<Figure>& row);
  /// Inline SVG markup (e.g. from svg_line_plot), inserted as given.
  void svg(const std::string& svg_markup, const std::string& caption = "");
  /// Markup inserted as given.
  void raw_html(const std::string& html);

  /// The complete document.
  std::string html() const;
  /// Writes html() atomically. Throws Error(path, ...).
  void write(const std::filesystem::path& path) const;

 private:
  void close_section();
  /// The open chapter (or the page without chapters) as markup: result part, data part, closed.
  std::string open_block() const;
  std::string& body() { return body_[part_ == Part::Result ? 0 : 1]; }
  int depth() const { return chapters_.empty() ? 0 : 1; }
  std::string title_;
  std::string done_;     ///< chapters already closed
  std::string body_[2];  ///< result part, data part of the open chapter (or of the page)
  std::vector<std::pair<std::string, std::string>> chapters_;  ///< id, heading
  Part part_ = Part::Result;
  bool in_section_ = false;
};

/// Escapes & < > " ' for HTML text and attributes.
std::string html_escape(const std::string& text);
/// Standard base64 (RFC 4648, with padding).
std::string base64_encode(const std::string& bytes);
/// "data:image/png;base64,..." for PNG bytes.
std::string png_data_uri(const std::string& png_bytes);

}  // namespace cropsight::report
