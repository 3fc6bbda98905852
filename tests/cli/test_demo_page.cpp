// `make demo` end to end: scripts/demo.sh runs the five systems into a temporary folder (a
// broccoli pass of 8 frames instead of 30, to save time) and writes the page with
// `cropsight report demo`; the page is then opened in headless Chromium, which must find the five
// chapters, each opening with its picture, and must have decoded every <img> and every image
// inside an <svg> and laid out every <svg>. Skipped with a message when Chromium is not installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "testing/testing.hpp"

namespace fs = std::filesystem;

namespace demo_page_test {

// Output of a shell command (stdout), as popen gives it.
std::string capture(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  pclose(p);
  return out;
}

std::string chromium_path() {
  std::string p = capture("command -v chromium || command -v chromium-browser");
  while (!p.empty() && (p.back() == '\n' || p.back() == '\r')) p.pop_back();
  return p.substr(0, p.find('\n'));
}

// The page with a script that writes what rendered into the DOM once everything loaded: every
// <img> decoded (the images inside an <svg> too: each gets an <img> probe of the same data, which
// the load event waits for), every <svg> laid out with an area, and per chapter whether the
// element after its heading holds a picture. The page itself has no script.
const char* kCheck = R"(<script>
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

nlohmann::json render_check(const std::string& chromium, const fs::path& page, const fs::path& dir) {
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

}  // namespace demo_page_test

TEST(DemoPage, TheDemoWritesFiveChaptersThatChromiumRenders) {
  using namespace demo_page_test;
  cropsight::testing::TempDir tmp;
  const fs::path build = cropsight::testing::cli_path().parent_path().parent_path();
  const fs::path demo = tmp / "demo";
  const std::string log =
      capture("cd " + cropsight::testing::shell_quoted(cropsight::testing::source_dir()) +
              " && DEMO_BROCCOLI_FRAMES=8 scripts/demo.sh " + cropsight::testing::shell_quoted(build) + " " +
              cropsight::testing::shell_quoted(demo) + " 2>&1; echo \"exit $?\"");
  ASSERT_NE(log.find("exit 0"), std::string::npos) << log;
  const fs::path page = demo / "index.html";
  ASSERT_TRUE(fs::exists(page)) << log;
  EXPECT_NE(log.find(fs::absolute(page).lexically_normal().string()), std::string::npos) << log;
  std::ifstream in(page);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);  // self-contained: nothing fetched
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);

  const std::string chromium = chromium_path();
  if (chromium.empty()) GTEST_SKIP() << "chromium not installed (command -v chromium): the page was not opened";
  const nlohmann::json r = render_check(chromium, page, tmp.path());
  ASSERT_TRUE(r.is_object()) << "chromium gave no render check";
  EXPECT_EQ(r["bad"], nlohmann::json::array()) << r.dump();
  EXPECT_GE(r["imgs"].get<int>(), 4) << r.dump();        // the broccoli frames and the sequence's
  EXPECT_GE(r["svg_images"].get<int>(), 4) << r.dump();  // one picture per other chapter
  const std::vector<std::string> ids = {"broccoli", "seedling", "potato", "grape", "detector"};
  ASSERT_EQ(r["chapters"].size(), ids.size()) << r.dump();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(r["chapters"][i]["id"], ids[i]);
    EXPECT_TRUE(r["chapters"][i]["picture_first"].get<bool>()) << ids[i] << " does not open with its picture";
  }
}

TEST(DemoPage, ReportDemoRefusesMissingSectionsBeforeWritingAnything) {
  using cropsight::testing::run_cli;
  using cropsight::testing::shell_quoted;
  cropsight::testing::TempDir tmp;
  fs::create_directories(tmp / "grape");
  const fs::path page = tmp / "page.html";
  auto r = run_cli("report demo --out " + shell_quoted(page));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--broccoli"), std::string::npos) << r.err;
  r = run_cli("report demo --grape " + shell_quoted(tmp / "grape") + " --out " + shell_quoted(page));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("truth.json"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(page));
  // `report` itself still needs its sequence and its page, now checked by the command.
  r = run_cli("report --out " + shell_quoted(page));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--data"), std::string::npos) << r.err;
}
