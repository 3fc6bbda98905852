// The demo page's chapters after the broccoli one (which the CLI adds: it runs the broccoli
// pipeline itself, as `cropsight report --model` does).
#include "cropsight/report/demo_page.hpp"

namespace cropsight::report {

void add_demo_chapters(HtmlPage& page, const DemoFolders& f) {
  struct Chapter {
    const std::filesystem::path& folder;
    SystemSummary (*summary)(const std::filesystem::path&);
    const char* title;
    const char* id;
  };
  const Chapter chapters[] = {
      {f.seedling, seedling_summary, "Broccoli seedlings from stereo", "seedling"},
      {f.potato, potato_summary, "Potato harvest loop", "potato"},
      {f.grape, grape_summary, "Grape bunches: labelled cloud and cut point", "grape"},
      {f.detector, detector_summary, "2D detector (CenterNet, ONNX)", "detector"},
  };
  for (const Chapter& c : chapters) {
    if (c.folder.empty()) continue;
    // The summary is read whole before its chapter opens: a missing file is an error before the
    // page has half a chapter.
    const SystemSummary s = c.summary(c.folder);
    page.chapter(c.title, c.id);
    add_system_summary(page, s);
  }
}

}  // namespace cropsight::report
