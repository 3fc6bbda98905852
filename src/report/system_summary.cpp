#include "cropsight/report/system_summary.hpp"

#include "cropsight/core/error.hpp"

namespace cropsight::report {

void add_system_summary(HtmlPage& page, const SystemSummary& s) {
  if (s.picture_svg.empty() && s.picture_pngs.empty()) throw Error("system summary", "no picture");
  if (!s.picture_svg.empty())
    page.svg(s.picture_svg, s.caption);
  else {
    page.figures(s.picture_pngs);
    if (!s.caption.empty()) page.paragraph(s.caption);
  }
  std::string figs = "<div class=\"figures\">";
  for (const auto& [what, value] : s.figures)
    figs += "<div><b>" + html_escape(value) + "</b><span>" + html_escape(what) + "</span></div>";
  page.raw_html(figs + "</div>");
  if (!s.note.empty()) page.raw_html("<p class=\"note\">" + html_escape(s.note) + "</p>");
  if (s.commands.empty()) return;
  std::string cmd = "<pre class=\"cmd\"><code>";
  for (const std::string& c : s.commands) cmd += html_escape(c) + "\n";
  page.raw_html(cmd + "</code></pre>");
}

}  // namespace cropsight::report
