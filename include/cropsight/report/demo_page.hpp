#pragma once
// The demo page (`cropsight report demo`, scripts/demo.sh): one chapter per system, each opening
// with its result picture, the figures the run measured and the commands that reproduce them
// (system_summary.hpp). Each system's chapter is made from one folder of files that the
// system's own commands wrote; nothing is computed here that the library does not compute
// (segmentation scores: eval::ConfusionMatrix; the grape cut point: pipeline::grape_cut_point).
// Every folder may hold commands.txt, the command lines that wrote it, shown on the page.
// The folders' layouts (docs/cli.md, "report demo"):
//
//   broccoli:  seq/ (simulate broccoli); the CLI runs the pipeline and its tracking evaluation
//              over it, as `cropsight report --model` does, and hands the result to
//              broccoli_summary(), then the broccoli report's own sections follow
//   seedling:  data/ (simulate seedling), detect.json + mask.png (detect seedling --out/--mask on
//              data/pair_000), disparity.png (stereo disparity on that pair), eval.json (eval
//              seedling --json on data/)
//   potato:    data/ (simulate potato), targets.jsonl (harvest potato --out), harvest.json
//              (harvest potato --json), eval.json (eval potato --json)
//   grape:     data/ (simulate grape: cloud.txt, truth.json), labelled.txt (segment grape --out),
//              segment.json (segment grape --json)
//   detector:  images/ (colour frames), objects/ (detect objects --out on images/),
//              detect.json (detect objects --json); labels/ (optional: each image's 16-bit
//              instance labels under the same name, the truth boxes)
//
// Every function throws Error(file, ...) naming the first missing or malformed file.
#include <filesystem>

#include "cropsight/pipeline/broccoli/tracking_eval.hpp"
#include "cropsight/report/broccoli_report.hpp"
#include "cropsight/report/html_page.hpp"
#include "cropsight/report/system_summary.hpp"

namespace cropsight::report {

/// Broccoli heads and the field map: the overlay frames of `data` (moved out of it, so that the
/// broccoli sections that follow do not show them twice), AP, map, size and time per frame.
SystemSummary broccoli_summary(const pipeline::broccoli::TrackingFigures& figures, BroccoliReportData& data,
                               const std::filesystem::path& dir);
/// Broccoli seedlings from stereo: the pair with the detected seedling outlined (truth in white),
/// the measured envelope, the SGM disparity.
SystemSummary seedling_summary(const std::filesystem::path& dir);
/// The potato harvest loop: one frame with the target's box, its 3D centre (projected), size and
/// angle. The frame: the middle one of the frames whose target is in full view with depth and angle.
SystemSummary potato_summary(const std::filesystem::path& dir);
/// Grape bunch segmentation: the labelled cloud seen from the camera and from the side, the true
/// labels beside it, the cut point; scores against the simulator's labels.
SystemSummary grape_summary(const std::filesystem::path& dir);
/// The 2D detector: the first image with the boxes scoring at least kDetectorShownScore.
SystemSummary detector_summary(const std::filesystem::path& dir);

/// The score a detector box needs to be drawn on the page (every box is in objects/).
inline constexpr double kDetectorShownScore = 0.3;

/// The chapters of the folders given (an empty path skips its system), in the order above, each
/// opened with HtmlPage::chapter.
struct DemoFolders {
  std::filesystem::path seedling, potato, grape, detector;
};
void add_demo_chapters(HtmlPage& page, const DemoFolders& folders);

}  // namespace cropsight::report
