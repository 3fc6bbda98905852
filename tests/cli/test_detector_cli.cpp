// train detector: a tiny VOC set trains end to end (model file, one progress line per epoch,
// JSON with the held-out images), eval detector scores the same held-out images, and bad sets are one line naming the
// file, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;
using cropsight::testing::TempDir;
using cropsight::testing::write_text;

void write_voc_set(const fs::path& dir, int n) {
  fs::create_directories(dir / "img");
  fs::create_directories(dir / "ann");
  for (int i = 0; i < n; ++i) {
    cropsight::ColorImage im(64, 64, cropsight::Rgb8{90, 90, 90});
    for (int y = 10 + i; y < 30 + i; ++y)
      for (int x = 12; x < 36; ++x) im.at(x, y) = cropsight::Rgb8{200, 150, 60};
    const std::string stem = "im" + std::to_string(i);
    cropsight::io::write_color(dir / "img" / (stem + ".png"), im);
    write_text(dir / "ann" / (stem + ".xml"), "<annotation><filename>" + stem +
                                                  ".png</filename><object><name>potato</name><bndbox><xmin>12</xmin>"
                                                  "<ymin>" +
                                                  std::to_string(10 + i) + "</ymin><xmax>36</xmax><ymax>" +
                                                  std::to_string(30 + i) + "</ymax></bndbox></object></annotation>");
  }
}

TEST(DetectorCli, TrainsOnAVocSetWithAHeldOutSplit) {
  TempDir t;
  write_voc_set(t.path(), 4);
  const auto r = run_cli("train detector --voc " + shell_quoted(t / "ann") + " --images " + shell_quoted(t / "img") +
                         " --classes potato --out " + shell_quoted(t / "det.pt") +
                         " --input-size 64x64 --width 8 --epochs 2 --val-split 0.25 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(t / "det.pt"));
  EXPECT_NE(r.err.find("epoch 2/2"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["train_images"], 3);
  EXPECT_EQ(j["val_images"].size(), 1u);
  EXPECT_EQ(j["log"].size(), 2u);
  // ONNX out, then both models through detect objects.
  const auto e =
      run_cli("export-detector --model " + shell_quoted(t / "det.pt") + " --out " + shell_quoted(t / "det.onnx"));
  ASSERT_EQ(e.exit_code, 0) << e.err;
  for (const char* m : {"det.pt", "det.onnx"}) {
    const auto d = run_cli("detect objects --model " + shell_quoted(t / m) + " --images " + shell_quoted(t / "img") +
                           " --out " + shell_quoted(t / (std::string(m) + ".out")) + " --json");
    ASSERT_EQ(d.exit_code, 0) << d.err;
    EXPECT_EQ(nlohmann::json::parse(d.out)["images"], 4);
    EXPECT_TRUE(fs::exists(t / (std::string(m) + ".out") / "detections.json"));
    EXPECT_TRUE(fs::exists(t / (std::string(m) + ".out") / "im0.txt"));
  }
  // --coco: detections.json carries the annotations' image ids; --overlay: a picture per image.
  write_text(t / "ids.json", R"({"images": [{"id": 17, "file_name": "img/im0.png"}, {"id": 3, "file_name": "im1.png"},
      {"id": 42, "file_name": "im2.png"}, {"id": 8, "file_name": "im3.png"}]})");
  auto d = run_cli("detect objects --model " + shell_quoted(t / "det.onnx") + " --images " + shell_quoted(t / "img") +
                   " --out " + shell_quoted(t / "ids.out") + " --coco " + shell_quoted(t / "ids.json") + " --overlay " +
                   shell_quoted(t / "pictures"));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const std::map<std::string, long> want = {{"im0.png", 17}, {"im1.png", 3}, {"im2.png", 42}, {"im3.png", 8}};
  for (const auto& det : nlohmann::json::parse(cropsight::io::read_file(t / "ids.out" / "detections.json")))
    EXPECT_EQ(det["image_id"].get<long>(), want.at(det["file_name"].get<std::string>())) << det.dump();
  for (const char* stem : {"im0", "im1", "im2", "im3"})
    EXPECT_TRUE(fs::exists(t / "pictures" / (std::string(stem) + ".png")));
  write_text(t / "short.json", R"({"images": [{"id": 1, "file_name": "im0.png"}]})");
  d = run_cli("detect objects --model " + shell_quoted(t / "det.onnx") + " --images " + shell_quoted(t / "img") +
              " --out " + shell_quoted(t / "short.out") + " --coco " + shell_quoted(t / "short.json"));
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("im1.png: is not among the images of"), std::string::npos) << d.err;
  EXPECT_FALSE(fs::exists(t / "short.out"));
  // eval detector scores the images train detector held out (same fraction and seed), both models.
  for (const char* m : {"det.pt", "det.onnx"}) {
    const auto ev = run_cli("eval detector --voc " + shell_quoted(t / "ann") + " --images " + shell_quoted(t / "img") +
                            " --model " + shell_quoted(t / m) + " --val-split 0.25 --json");
    ASSERT_EQ(ev.exit_code, 0) << ev.err;
    const auto k = nlohmann::json::parse(ev.out);
    EXPECT_EQ(k["images"], 1);
    EXPECT_EQ(k["image_names"], j["val_images"]);
    ASSERT_EQ(k["classes"].size(), 1u);
    EXPECT_EQ(k["classes"][0]["class"], "potato");
    EXPECT_EQ(k["classes"][0]["truths"], 1);
    EXPECT_TRUE(k["classes"][0].contains("box_ap50_95"));
  }
  write_text(t / "bad.json",
             R"({"images": [{"id": 1, "file_name": "im0.png"}], "categories": [{"id": 1, "name": "potato"}]})");
  const auto bad_ann = run_cli("eval detector --coco " + shell_quoted(t / "bad.json") + " --images " +
                               shell_quoted(t / "img") + " --model " + shell_quoted(t / "det.onnx"));
  EXPECT_EQ(bad_ann.exit_code, 2);
  EXPECT_NE(bad_ann.err.find("bad.json"), std::string::npos) << bad_ann.err;
  const auto bad = run_cli("detect objects --model " + shell_quoted(t / "img" / "im0.png") + " --images " +
                           shell_quoted(t / "img") + " --out " + shell_quoted(t / "o"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("im0.png"), std::string::npos) << bad.err;
}

// The same images as COCO with polygons (masks): train detector calibrates its per-class mask
// thresholds on its training images, tune-mask-thresholds does it for an existing model, the ONNX
// export carries them and eval detector uses them; a set without masks cannot calibrate.
TEST(DetectorCli, MaskThresholdsAreCalibratedOnTrainingImagesAndTravel) {
  TempDir t;
  write_voc_set(t.path(), 4);
  nlohmann::json coco = {{"categories", {{{"id", 1}, {"name", "potato"}}}}};
  for (int i = 0; i < 4; ++i) {
    coco["images"].push_back(
        {{"id", i + 1}, {"file_name", "im" + std::to_string(i) + ".png"}, {"width", 64}, {"height", 64}});
    const double y0 = 10 + i, y1 = 30 + i;
    coco["annotations"].push_back({{"id", i + 1},
                                   {"image_id", i + 1},
                                   {"category_id", 1},
                                   {"bbox", {12, y0, 24, 20}},
                                   {"area", 480},
                                   {"iscrowd", 0},
                                   {"segmentation", {{12, y0, 36, y0, 36, y1, 12, y1}}}});
  }
  write_text(t / "coco.json", coco.dump());
  const std::string set = " --coco " + shell_quoted(t / "coco.json") + " --images " + shell_quoted(t / "img");
  const auto tr = run_cli("train detector" + set + " --out " + shell_quoted(t / "det.pt") +
                          " --input-size 64x64 --width 8 --epochs 2 --val-split 0.25 --json");
  ASSERT_EQ(tr.exit_code, 0) << tr.err;
  EXPECT_NE(tr.err.find("mask thresholds per class"), std::string::npos) << tr.err;
  const auto trained = nlohmann::json::parse(tr.out)["mask_thresholds"];
  ASSERT_EQ(trained.size(), 1u);
  EXPECT_GT(trained[0].get<double>(), 0.0);
  EXPECT_LT(trained[0].get<double>(), 1.0);

  const auto cal = run_cli("tune-mask-thresholds --model " + shell_quoted(t / "det.pt") + set +
                           " --val-split 0.25 --out " + shell_quoted(t / "cal.pt") + " --json");
  ASSERT_EQ(cal.exit_code, 0) << cal.err;
  const auto cj = nlohmann::json::parse(cal.out);
  EXPECT_EQ(cj["images"], 3);                 // the split's training images only
  EXPECT_EQ(cj["mask_thresholds"], trained);  // the same images and weights: the same choice
  ASSERT_EQ(run_cli("export-detector --model " + shell_quoted(t / "cal.pt") + " --out " + shell_quoted(t / "cal.onnx"))
                .exit_code,
            0);
  for (const char* m : {"cal.pt", "cal.onnx"}) {
    const auto ev = run_cli("eval detector" + set + " --model " + shell_quoted(t / m) + " --val-split 0.25 --json");
    ASSERT_EQ(ev.exit_code, 0) << ev.err;
    EXPECT_EQ(nlohmann::json::parse(ev.out)["mask_thresholds"], trained) << m;
    const auto flat = run_cli("eval detector" + set + " --model " + shell_quoted(t / m) +
                              " --val-split 0.25 --mask-threshold 0.3 --json");
    ASSERT_EQ(flat.exit_code, 0) << flat.err;
    EXPECT_EQ(nlohmann::json::parse(flat.out)["mask_thresholds"], nlohmann::json::array({0.3})) << m;
  }
  // Another inference input and mask upsampling: calibrated for, and carried into the ONNX file.
  const auto big = run_cli("tune-mask-thresholds --model " + shell_quoted(t / "det.pt") + set +
                           " --val-split 0.25 --input-size 96x96 --mask-upsampling nearest --flip-test --out " +
                           shell_quoted(t / "big.pt") + " --json");
  ASSERT_EQ(big.exit_code, 0) << big.err;
  EXPECT_EQ(nlohmann::json::parse(big.out)["input"], "96x96");
  EXPECT_EQ(nlohmann::json::parse(big.out)["mask_upsampling"], "nearest");
  EXPECT_EQ(nlohmann::json::parse(big.out)["flip_test"], true);
  ASSERT_EQ(run_cli("export-detector --model " + shell_quoted(t / "big.pt") + " --out " + shell_quoted(t / "big.onnx"))
                .exit_code,
            0);
  for (const char* m : {"big.pt", "big.onnx", "cal.onnx"}) {
    const auto ev = run_cli("eval detector" + set + " --model " + shell_quoted(t / m) + " --val-split 0.25 --json");
    ASSERT_EQ(ev.exit_code, 0) << ev.err;
    const auto j = nlohmann::json::parse(ev.out);
    const bool cal_model = std::string(m) == "cal.onnx";
    EXPECT_EQ(j["input"], cal_model ? "64x64" : "96x96") << m;
    EXPECT_EQ(j["mask_upsampling"], cal_model ? "bilinear" : "nearest") << m;
    EXPECT_EQ(j["flip_test"], !cal_model) << m;
  }
  // The multi-scale mask test and turning the flip test off travel the same way.
  const auto ms =
      run_cli("tune-mask-thresholds --model " + shell_quoted(t / "big.pt") + set +
              " --val-split 0.25 --flip-test=false --mask-inputs 128x128 --mask-inputs-flip-test=false --out " +
              shell_quoted(t / "ms.pt") + " --json");
  ASSERT_EQ(ms.exit_code, 0) << ms.err;
  EXPECT_EQ(nlohmann::json::parse(ms.out)["flip_test"], false);
  EXPECT_EQ(nlohmann::json::parse(ms.out)["mask_inputs"], "128x128");
  ASSERT_EQ(run_cli("export-detector --model " + shell_quoted(t / "ms.pt") + " --out " + shell_quoted(t / "ms.onnx"))
                .exit_code,
            0);
  for (const char* m : {"ms.pt", "ms.onnx"}) {
    const auto ev = run_cli("eval detector" + set + " --model " + shell_quoted(t / m) + " --val-split 0.25 --json");
    ASSERT_EQ(ev.exit_code, 0) << ev.err;
    const auto j = nlohmann::json::parse(ev.out);
    EXPECT_EQ(j["mask_inputs"], "128x128") << m;
    EXPECT_EQ(j["flip_test"], false) << m;
    EXPECT_EQ(j["mask_inputs_flip_test"], false) << m;
  }
  const auto cleared = run_cli("tune-mask-thresholds --model " + shell_quoted(t / "ms.pt") + set +
                               " --val-split 0.25 --mask-inputs none --out " + shell_quoted(t / "one.pt") + " --json");
  ASSERT_EQ(cleared.exit_code, 0) << cleared.err;
  EXPECT_EQ(nlohmann::json::parse(cleared.out)["mask_inputs"], "");
  for (const char* bad : {" --input-size 90x90", " --input-size 96", " --mask-upsampling cubic",
                          " --mask-inputs 100x96", " --mask-inputs 128x128,big"}) {
    const auto r = run_cli("tune-mask-thresholds --model " + shell_quoted(t / "det.pt") + set + bad + " --out " +
                           shell_quoted(t / "bad.pt"));
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(t / "bad.pt")) << bad;
  }
  // Boxes only (VOC): nothing to calibrate, one line naming the set, no output.
  const auto none =
      run_cli("tune-mask-thresholds --model " + shell_quoted(t / "det.pt") + " --voc " + shell_quoted(t / "ann") +
              " --images " + shell_quoted(t / "img") + " --out " + shell_quoted(t / "none.pt"));
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("ann"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("no training image has masks"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(t / "none.pt"));
}

TEST(DetectorCli, BadSetsAreOneLineExitTwo) {
  TempDir t;
  write_text(t / "ann.json", R"({"images": [], "categories": [{"id": 1, "name": "x"}]})");
  fs::create_directories(t / "images");  // the model goes beside the images, never into them
  auto r = run_cli("train detector --coco " + shell_quoted(t / "ann.json") + " --images " + shell_quoted(t / "images") +
                   " --out " + shell_quoted(t / "m.pt"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("ann.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'annotations'"), std::string::npos) << r.err;
  r = run_cli("train detector --images " + shell_quoted(t / "images") + " --out " + shell_quoted(t / "m.pt"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--coco"), std::string::npos) << r.err;
  // A key outside the detector.* / augment.* sections, or a misspelt one inside, is an error, not
  // silently ignored: one line naming it, no model file.
  write_voc_set(t.path(), 2);
  for (const char* bad : {"mask_weight=3", "detector.mask_wieght=3"}) {
    r = run_cli("train detector --voc " + shell_quoted(t / "ann") + " --images " + shell_quoted(t / "img") +
                " --classes potato --epochs 1 --input-size 64x64 --out " + shell_quoted(t / "m.pt") + " --set " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find(std::string(bad).substr(0, std::string(bad).find('='))), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(t / "m.pt")) << bad;
  }
}

}  // namespace
