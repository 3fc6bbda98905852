// The demo page's chapters after the broccoli one (which the CLI adds: it runs the broccoli
// pipeline itself, as `cropsight report --model` does).
#include "cropsight/report/demo_page.hpp"

namespace cropsight::report {

void add_demo_chapters(HtmlPage& page, const DemoFolders& f) {
  // Each summary is read whole before its chapter opens: a missing file is an error before the
  // page has half a chapter.
  if (!f.seedling.empty()) {
    const SystemSummary s = seedling_summary(f.seedling);
    page.chapter("Broccoli seedlings from stereo", "seedling");
    add_system_summary(page, s);
  }
  if (!f.potato.empty()) {
    const SystemSummary s = potato_summary(f.potato);
    page.chapter("Potato harvest loop", "potato");
    add_system_summary(page, s);
  }
  if (!f.grape.empty()) {
    const SystemSummary s = grape_summary(f.grape);
    page.chapter("Grape bunches: labelled cloud and cut point", "grape");
    add_system_summary(page, s);
  }
  if (!f.detector.empty()) {
    const SystemSummary s = detector_summary(f.detector);
    page.chapter("2D detector (CenterNet, ONNX)", "detector");
    add_system_summary(page, s);
  }
}

}  // namespace cropsight::report
