#pragma once
// Headless Chromium for the CLI tests that write pages (report demo, report): find it, open a page
// and read back what rendered. Tests skip with a message when Chromium is not installed.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "testing/testing.hpp"

namespace cropsight::testing {

// Output of a shell command (stdout), as popen gives it.
inline std::string capture(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  pclose(p);
  return out;
}

inline std::string chromium_path() {
  std::string p = capture("command -v chromium || command -v chromium-browser");
  while (!p.empty() && (p.back() == '\n' || p.back() == '\r')) p.pop_back();
  return p.substr(0, p.find('\n'));
}

// The page with a script that writes what rendered into the DOM once everything loaded: every
// <img> decoded (the images inside an <svg> too: each gets an <img> probe of the same data, which
// the load event waits for), every <svg> laid out with an area, and per chapter whether the
// element after its heading holds a picture. The page itself has no script.
inline const char* kCheck = R"(<script>
const probes = [...document.querySelectorAll('svg image')].map(el => {
  const im = document.createElement('img');
  im.className = 'probe';
  im.src = el.getAttribute('href');
  document.body.appendChild(im);
  return im;
});
window.addEventListener('load', () => {
  const bad = [];
  [...document.images].forEach((im, i) => {
    if (!im.complete || im.naturalWidth === 0) bad.push((im.className === 'probe' ? 'svg image ' : 'img ') + i);
  });
  const svgs = [...document.querySelectorAll('svg')];
  svgs.forEach((s, i) => { const r = s.getBoundingClientRect(); if (r.width < 10 || r.height < 10) bad.push('svg ' + i); });
  const chapters = [...document.querySelectorAll('article.system')].map(a => ({
    id: a.id, picture_first: !!(a.children[1] && a.children[1].querySelector('img, svg')) }));
  const out = document.createElement('pre');
  out.id = 'render-check';
  out.textContent = JSON.stringify({imgs: document.images.length - probes.length, svg_images: probes.length,
                                    svgs: svgs.length, bad, chapters});
  document.body.appendChild(out);
});
</script>
)";

inline nlohmann::json render_check(const std::string& chromium, const std::filesystem::path& page,
                                   const std::filesystem::path& dir) {
  std::ifstream in(page);
  std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  html.insert(html.rfind("</body>"), kCheck);
  std::ofstream(dir / "check.html") << html;
  const std::string dom =
      capture(chromium +
              " --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking"
              " --disable-component-update --disable-sync --virtual-time-budget=20000"
              " --user-data-dir=" +
              cropsight::testing::shell_quoted(dir / "profile") + " --dump-dom file://" +
              (dir / "check.html").string() + " 2>/dev/null");
  const auto at = dom.find("id=\"render-check\">");
  if (at == std::string::npos) return nullptr;
  const auto from = dom.find('>', at) + 1;
  std::string text = dom.substr(from, dom.find("</pre>", from) - from);
  for (std::size_t p; (p = text.find("&quot;")) != std::string::npos;) text.replace(p, 6, "\"");
  return nlohmann::json::parse(text, nullptr, false);
}

}  // namespace cropsight::testing
