#include "cropsight/report/html_page.hpp"

#include <algorithm>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"

namespace cropsight::report {

namespace {
// Inline style sheet: readable on screen and in print, no external fonts.
constexpr const char* kCss = R"(
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:0 auto;max-width:1200px;padding:1em 2em;color:#222;background:#fafafa}
h1{font-size:1.6em;border-bottom:2px solid #3a7;padding-bottom:.2em}
h2{font-size:1.3em;margin-top:1.6em;color:#264}
h3{font-size:1.05em}
section{margin-bottom:1.5em}
table{border-collapse:collapse;margin:.5em 0 1em 0;font-size:.92em}
th,td{border:1px solid #ccc;padding:.25em .6em;text-align:left}
th{background:#e8f2ec}
td.num{text-align:right;font-variant-numeric:tabular-nums}
caption{caption-side:bottom;font-size:.85em;color:#666;padding-top:.3em;text-align:left}
.figs{display:flex;flex-wrap:wrap;gap:.8em;margin:.5em 0 1em 0}
figure{margin:0;background:#fff;border:1px solid #ddd;padding:.4em}
figure img{display:block;max-width:372px;height:auto}
figcaption{font-size:.85em;color:#555;padding-top:.3em}
.svg{background:#fff;border:1px solid #ddd;display:inline-block;padding:.4em;margin:.5em 0}
footer{margin-top:2em;font-size:.8em;color:#888}
nav ol{columns:2;font-size:.95em}
article.system{border-top:3px solid #3a7;margin-top:2em}
article.system>h2{font-size:1.45em}
.figures{display:flex;flex-wrap:wrap;gap:.6em;margin:.6em 0}
.figures div{background:#fff;border:1px solid #ddd;padding:.4em .8em;min-width:9em}
.figures b{display:block;font-size:1.25em;font-variant-numeric:tabular-nums}
.figures span{font-size:.85em;color:#555}
pre.cmd{background:#263238;color:#e8eaf6;padding:.6em .8em;overflow-x:auto;font-size:.85em}
p.note{font-size:.9em;color:#555;border-left:3px solid #da3;padding-left:.6em}
svg.overlay{max-width:100%;height:auto;display:block}
)";

bool looks_numeric(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == ' ' || c == '%' || c == 'x'))
      return false;
  return s.front() == '-' || (s.front() >= '0' && s.front() <= '9');
}
}  // namespace

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string base64_encode(const std::string& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t(std::uint8_t(bytes[i])) << 16) |
                            (std::uint32_t(std::uint8_t(bytes[i + 1])) << 8) | std::uint8_t(bytes[i + 2]);
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += kAlphabet[(n >> 6) & 63];
    out += kAlphabet[n & 63];
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t n = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t n =
        (std::uint32_t(std::uint8_t(bytes[i])) << 16) | (std::uint32_t(std::uint8_t(bytes[i + 1])) << 8);
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += kAlphabet[(n >> 6) & 63];
    out += '=';
  }
  return out;
}

std::string png_data_uri(const std::string& png_bytes) { return "data:image/png;base64," + base64_encode(png_bytes); }

Figure make_figure(const ColorImage& image, std::string caption, int display_width) {
  return Figure{io::encode_png(image), std::move(caption), display_width};
}

HtmlPage::HtmlPage(std::string title) : title_(std::move(title)) {}

void HtmlPage::close_section() {
  if (in_section_) body() += "</section>\n";
  in_section_ = false;
}

void HtmlPage::section(const std::string& heading_text, Part part) {
  close_section();
  part_ = part;
  const std::string tag = "h" + std::to_string(2 + depth());
  body() += "<section>\n<" + tag + ">" + html_escape(heading_text) + "</" + tag + ">\n";
  in_section_ = true;
}

void HtmlPage::chapter(const std::string& heading_text, const std::string& id) {
  const bool valid = !id.empty() && std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-';
  });
  if (!valid) throw Error("chapter", "'" + id + "' is not an id (letters, digits and '-')");
  for (const auto& c : chapters_)
    if (c.first == id) throw Error("chapter", "id '" + id + "' used twice");
  done_ += open_block();
  body_[0].clear();
  body_[1].clear();
  in_section_ = false;
  part_ = Part::Result;
  chapters_.emplace_back(id, heading_text);
}

std::string HtmlPage::open_block() const {
  std::string out;
  if (!chapters_.empty())
    out += "<article class=\"system\" id=\"" + chapters_.back().first + "\">\n<h2>" +
           html_escape(chapters_.back().second) + "</h2>\n";
  // Results, then data; the section still open is closed where it stands.
  for (const Part part : {Part::Result, Part::Data}) {
    out += body_[part == Part::Result ? 0 : 1];
    if (in_section_ && part == part_) out += "</section>\n";
  }
  if (!chapters_.empty()) out += "</article>\n";
  return out;
}

void HtmlPage::heading(const std::string& text, int level) {
  level += depth();
  level = level < 2 ? 2 : level > 6 ? 6 : level;
  const std::string tag = "h" + std::to_string(level);
  body() += "<" + tag + ">" + html_escape(text) + "</" + tag + ">\n";
}

void HtmlPage::paragraph(const std::string& text) { body() += "<p>" + html_escape(text) + "</p>\n"; }

void HtmlPage::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                     const std::string& caption) {
  body() += "<table>\n";
  if (!caption.empty()) body() += "<caption>" + html_escape(caption) + "</caption>\n";
  if (!header.empty()) {
    body() += "<thead><tr>";
    for (const auto& h : header) body() += "<th>" + html_escape(h) + "</th>";
    body() += "</tr></thead>\n";
  }
  body() += "<tbody>\n";
  for (const auto& row : rows) {
    body() += "<tr>";
    for (const auto& cell : row)
      body() += (looks_numeric(cell) ? "<td class=\"num\">" : "<td>") + html_escape(cell) + "</td>";
    body() += "</tr>\n";
  }
  body() += "</tbody></table>\n";
}

void HtmlPage::key_values(const std::vector<std::pair<std::string, std::string>>& rows, const std::string& caption) {
  std::vector<std::vector<std::string>> cells;
  cells.reserve(rows.size());
  for (const auto& [k, v] : rows) cells.push_back({k, v});
  table({"field", "value"}, cells, caption);
}

void HtmlPage::figures(const std::vector<Figure>& row) {
  body() += "<div class=\"figs\">\n";
  for (const auto& f : row) {
    body() += "<figure><img alt=\"" + html_escape(f.caption) + "\" src=\"" + png_data_uri(f.png) + "\"";
    if (f.display_width > 0) body() += " width=\"" + std::to_string(f.display_width) + "\"";
    body() += "><figcaption>" + html_escape(f.caption) + "</figcaption></figure>\n";
  }
  body() += "</div>\n";
}

void HtmlPage::svg(const std::string& svg_markup, const std::string& caption) {
  body() += "<figure class=\"svg\">" + svg_markup;
  if (!caption.empty()) body() += "<figcaption>" + html_escape(caption) + "</figcaption>";
  body() += "</figure>\n";
}

void HtmlPage::raw_html(const std::string& html_text) { body() += html_text + "\n"; }

std::string HtmlPage::html() const {
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += "<title>" + html_escape(title_) + "</title>\n<style>" + kCss + "</style>\n</head>\n<body>\n";
  out += "<h1>" + html_escape(title_) + "</h1>\n";
  if (!chapters_.empty()) {
    out += "<nav><ol>";
    for (const auto& [id, text] : chapters_) out += "<li><a href=\"#" + id + "\">" + html_escape(text) + "</a></li>";
    out += "</ol></nav>\n";
  }
  out += done_ + open_block();
  out += "<footer>Generated by cropsight 0.1.0. Self-contained: every image is embedded.</footer>\n";
  out += "</body>\n</html>\n";
  return out;
}

void HtmlPage::write(const std::filesystem::path& path) const { io::write_file_atomic(path, html()); }

}  // namespace cropsight::report
