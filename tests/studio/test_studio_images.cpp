// The studio on a folder of images (--images) over real HTTP: who may talk to it, what it does
// with bad bodies, that boxes and polygons land as COCO, VOC and YOLO in DIR/cropsight-labels/
// and nowhere else, and that no file the studio did not write is ever replaced.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <thread>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/image_labels.hpp"
#include "cropsight/io/voc.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "cropsight/studio/image_label_store.hpp"
#include "studio_fixture.hpp"
#include "testing/testing.hpp"

namespace cropsight::studio_testing {

namespace fs = std::filesystem;

namespace images_test {

// Three 64×48 images (a bright blob on a dark background) and a note of the user's.
fs::path image_folder(const fs::path& dir) {
  const fs::path images = dir / "images";
  fs::create_directories(images);
  for (int k = 0; k < 3; ++k) {
    ColorImage im(64, 48);
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) {
        const bool blob = (x - 20 - 8 * k) * (x - 20 - 8 * k) + (y - 24) * (y - 24) < 100;
        im.at(x, y) = blob ? Rgb8{150, 110, 70} : Rgb8{250, 250, 250};
      }
    io::write_color(images / ("img_" + std::to_string(k) + ".png"), im);
  }
  testing::write_text(images / "notes.txt", "the user's own notes");
  return images;
}

studio::StudioOptions images_options(const fs::path& images) {
  studio::StudioOptions o;
  o.images = images;
  o.max_body_bytes = 1u << 20;
  return o;
}

std::map<std::string, std::uintmax_t> files_under(const fs::path& dir) {
  std::map<std::string, std::uintmax_t> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename() != ".cropsight-studio.lock")
      out[e.path().string()] = e.is_regular_file() ? e.file_size() : 0;
  return out;
}

const std::string kTwoShapes =
    R"({"shapes": [{"label": "potato", "box": [4, 6, 30.5, 40]},
                   {"label": "sprout", "polygon": [40, 10, 60, 12, 50, 30]}]})";

}  // namespace images_test

using namespace images_test;

TEST(StudioImages, RefusesRequestsWithoutTokenOrForeignHost) {
  testing::TempDir dir;
  RunningStudio studio(images_options(image_folder(dir.path())));
  auto anonymous = studio.anonymous();
  EXPECT_EQ(anonymous.Get("/api/info")->status, 403);
  EXPECT_EQ(anonymous.Get("/api/image/0/pixels")->status, 403);
  EXPECT_EQ(anonymous.Post("/api/image/0/labels", kTwoShapes, "application/json")->status, 403);
  auto client = studio.client();
  EXPECT_EQ(
      client.Get("/api/image/0/labels", {{"Host", "evil.example:" + std::to_string(studio.server().port())}})->status,
      403);
  EXPECT_FALSE(fs::exists(dir / "images" / studio::kImageLabelsFolder));
  const auto info = nlohmann::json::parse(client.Get("/api/info")->body);
  EXPECT_EQ(info["mode"], "images");
  EXPECT_EQ(info["images"], nlohmann::json({"img_0.png", "img_1.png", "img_2.png"}));
  EXPECT_EQ(info["classes"], nlohmann::json({"potato"}));  // the potato detector's
  const auto page = client.Get("/");
  EXPECT_NE(page->body.find("images.js"), std::string::npos);  // the image page, not the depth page
  EXPECT_EQ(client.Get("/images.js")->status, 200);
}

TEST(StudioImages, ServesOnlyItsImagesAndNothingOutside) {
  testing::TempDir dir;
  const fs::path images = image_folder(dir.path());
  testing::write_text(dir / "secret.txt", "outside the folder");
  fs::create_symlink(dir / "secret.txt", images / "secret.png");  // a link out is not an image of the folder
  fs::create_symlink(images / "img_0.png", images / "same.png");  // a link inside is
  RunningStudio studio(images_options(images));
  auto client = studio.client();
  const auto pixels = client.Get("/api/image/2/pixels");
  EXPECT_EQ(pixels->status, 200);
  EXPECT_EQ(pixels->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(pixels->body, io::read_file(images / "img_2.png"));
  EXPECT_EQ(nlohmann::json::parse(client.Get("/api/info")->body)["images"],
            nlohmann::json({"img_0.png", "img_1.png", "img_2.png", "same.png"}));
  for (const std::string& path : std::vector<std::string>{
           "/api/image/4/pixels", "/api/image/-1/labels", "/api/image/99999999999999/labels", "/api/image/../labels",
           "/api/image/%2e%2e/labels", "/api/image/0/../../secret.txt", "/files/../secret.txt",
           "/files/%2e%2e/secret.txt", "/files/.cropsight-studio.lock", "/api/frame/0/labels", "/api/train"}) {
    const auto r = client.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_GE(r->status, 400) << path;
    EXPECT_LT(r->status, 500) << path;
    EXPECT_EQ(r->body.find("outside the folder"), std::string::npos) << path;
  }
}

TEST(StudioImages, RefusesOversizedAndMalformedBodiesAndWritesNothing) {
  testing::TempDir dir;
  const fs::path images = image_folder(dir.path());
  RunningStudio studio(images_options(images));
  auto client = studio.client();
  const auto before = files_under(dir.path());
  EXPECT_EQ(client.Post("/api/image/0/labels", std::string(2u << 20, ' '), "application/json")->status, 413);
  const std::string nan_box = R"({"shapes": [{"label": "potato", "box": [0, 0, NaN, 4]}]})";
  for (const std::string& body : std::vector<std::string>{
           "",
           "{",
           "[]",
           "null",
           R"({"shapes": 3})",
           R"({"shapes": [3]})",
           R"({"shapes": [{"box": [0, 0, 4, 4]}]})",
           R"({"shapes": [{"label": "potato"}]})",
           R"({"shapes": [{"label": "potato", "box": [0, 0, 4]}]})",
           R"({"shapes": [{"label": "potato", "box": [5, 5, 4, 9]}]})",
           R"({"shapes": [{"label": "potato", "box": [70, 50, 90, 60]}]})",  // empty once clamped into 64×48
           R"({"shapes": [{"label": "potato", "box": ["0", 0, 4, 4]}]})",
           nan_box,
           R"({"shapes": [{"label": "potato", "box": [0, 0, 1e999, 4]}]})",
           R"({"shapes": [{"label": "", "box": [0, 0, 4, 4]}]})",
           R"({"shapes": [{"label": "a\nb", "box": [0, 0, 4, 4]}]})",
           R"({"shapes": [{"label": " potato", "box": [0, 0, 4, 4]}]})",
           R"({"shapes": [{"label": "potato", "box": [0, 0, 4, 4], "polygon": [0, 0, 4, 0, 4, 4]}]})",
           R"({"shapes": [{"label": "potato", "polygon": [0, 0, 4, 0]}]})",
           R"({"shapes": [{"label": "potato", "polygon": [0, 0, 4, 0, 4]}]})",
           R"({"shapes": [{"label": "potato", "polygon": [1, 1, 1, 1, 1, 1]}]})",
           "{\"shapes\": [{\"label\": \"" + std::string(65, 'x') + "\", \"box\": [0, 0, 4, 4]}]}"})
    EXPECT_EQ(client.Post("/api/image/0/labels", body, "application/json")->status, 400) << body;
  EXPECT_EQ(client.Post("/api/image/3/labels", kTwoShapes, "application/json")->status, 404);
  EXPECT_EQ(client.Post("/api/image/99999999999999/labels", kTwoShapes, "application/json")->status, 404);
  EXPECT_EQ(files_under(dir.path()), before);
}

TEST(StudioImages, SavesCocoVocAndYoloIntoItsOwnFolderAndReadsThemBack) {
  testing::TempDir dir;
  const fs::path images = image_folder(dir.path());
  const auto before = files_under(images);
  {
    RunningStudio studio(images_options(images));
    auto client = studio.client();
    ASSERT_EQ(client.Post("/api/image/1/labels", kTwoShapes, "application/json")->status, 200);
    ASSERT_EQ(client.Post("/api/image/2/labels", R"({"shapes": []})", "application/json")->status, 200);
    const auto info = nlohmann::json::parse(client.Get("/api/info")->body);
    EXPECT_EQ(info["labelled"], nlohmann::json({1, 2}));
    EXPECT_EQ(info["classes"], nlohmann::json({"potato", "sprout"}));
  }
  // Only cropsight-labels/ is new in the image folder; the lock is gone.
  auto after = files_under(images);
  for (const auto& [path, size] : before) EXPECT_EQ(after[path], size) << path;
  const fs::path out = images / studio::kImageLabelsFolder;
  for (const auto& [path, size] : after) EXPECT_TRUE(before.count(path) || path.rfind(out.string(), 0) == 0) << path;
  EXPECT_FALSE(fs::exists(images / ".cropsight-studio.lock"));

  const io::LabelSet coco = io::read_coco_labels(out / "coco.json");
  ASSERT_EQ(coco.images.size(), 2u);
  EXPECT_EQ(coco.images[0].file_name, "img_1.png");
  EXPECT_EQ(coco.images[0].width, 64);
  ASSERT_EQ(coco.images[0].shapes.size(), 2u);
  const io::LabelShape& box = coco.images[0].shapes[0];
  EXPECT_EQ(box.label, "potato");
  EXPECT_EQ(std::vector<double>({box.x1, box.y1, box.x2, box.y2}), std::vector<double>({4, 6, 30.5, 40}));
  const io::LabelShape& polygon = coco.images[0].shapes[1];
  ASSERT_EQ(polygon.polygons.size(), 1u);
  EXPECT_EQ(polygon.polygons[0].size(), 3u);
  EXPECT_EQ(std::vector<double>({polygon.x1, polygon.y1, polygon.x2, polygon.y2}),
            std::vector<double>({40, 10, 60, 30}));
  EXPECT_TRUE(coco.images[1].shapes.empty());  // saved without shapes: labelled, no object
  const io::VocAnnotation voc = io::read_voc(out / "voc" / "img_1.xml");
  ASSERT_EQ(voc.objects.size(), 2u);
  EXPECT_EQ(voc.objects[1].name, "sprout");
  EXPECT_DOUBLE_EQ(voc.objects[1].xmax, 60);
  EXPECT_EQ(io::read_file(out / "yolo" / "classes.txt"), "potato\nsprout\n");
  EXPECT_EQ(io::read_file(out / "yolo" / "img_1.txt"),
            "0 0.26953125 0.4791666667 0.4140625 0.7083333333\n1 0.78125 0.4166666667 0.3125 0.4166666667\n");
  EXPECT_EQ(io::read_file(out / "yolo" / "img_2.txt"), "");

  // A new studio shows the saved labels (they win over the model's boxes, which the page
  // shows only on unlabelled images).
  {
    RunningStudio again(images_options(images));
    const auto labels = nlohmann::json::parse(again.client().Get("/api/image/1/labels")->body);
    EXPECT_TRUE(labels["labelled"].get<bool>());
    EXPECT_EQ(labels["shapes"][0]["box"], nlohmann::json({4, 6, 30.5, 40}));
    EXPECT_EQ(labels["shapes"][1]["polygon"], nlohmann::json({40, 10, 60, 12, 50, 30}));
    EXPECT_FALSE(nlohmann::json::parse(again.client().Get("/api/image/0/labels")->body)["labelled"].get<bool>());
    EXPECT_EQ(again.client().Get("/api/image/0/proposals")->status, 200);
  }

  // An image moved out of the folder keeps its labels in coco.json through later saves.
  fs::rename(images / "img_1.png", dir / "img_1.png");
  RunningStudio without(images_options(images));
  EXPECT_EQ(nlohmann::json::parse(without.client().Get("/api/info")->body)["labelled"], nlohmann::json({1}));  // img_2
  ASSERT_EQ(without.client().Post("/api/image/0/labels", kTwoShapes, "application/json")->status, 200);
  const io::LabelSet kept = io::read_coco_labels(out / "coco.json");
  ASSERT_EQ(kept.images.size(), 3u);
  EXPECT_EQ(kept.images[2].file_name, "img_1.png");
  EXPECT_EQ(kept.images[2].shapes.size(), 2u);
}

TEST(StudioImages, NeverReplacesAFileItDidNotWrite) {
  testing::TempDir dir;
  const fs::path images = image_folder(dir.path());
  const fs::path out = images / studio::kImageLabelsFolder;
  // A folder of that name the user made: the studio refuses to start on it.
  fs::create_directories(out);
  testing::write_text(out / "coco.json", "{}");
  EXPECT_THROW(studio::StudioServer{images_options(images)}, Error);
  EXPECT_EQ(io::read_file(out / "coco.json"), "{}");
  fs::remove_all(out);

  // A file the user put into the studio's folder: that save is refused, the file kept.
  {
    RunningStudio studio(images_options(images));
    ASSERT_EQ(studio.client().Post("/api/image/0/labels", kTwoShapes, "application/json")->status, 200);
  }
  testing::write_text(out / "voc" / "img_1.xml", "the user's");
  RunningStudio studio(images_options(images));
  EXPECT_EQ(studio.client().Post("/api/image/1/labels", kTwoShapes, "application/json")->status, 409);
  EXPECT_EQ(io::read_file(out / "voc" / "img_1.xml"), "the user's");
  EXPECT_FALSE(fs::exists(out / "yolo" / "img_1.txt"));
  const auto info = nlohmann::json::parse(studio.client().Get("/api/info")->body);
  EXPECT_EQ(info["labelled"], nlohmann::json({0}));  // the refused save left no trace in the store either
  EXPECT_EQ(studio.client().Post("/api/image/2/labels", kTwoShapes, "application/json")->status, 200);
}

// On a real grape image (the drawn blobs of image_folder() hold no grapes): the shipped CenterNet's
// bunches and peduncles, each a box inside the image with one of its classes.
TEST(StudioImages, ProposalsFromTheProjectsOwnDetector) {
  const fs::path grape_image = cropsight::testing::shared_data_dir() / "grape/coco_train/JPEGImages/grape_image_1.jpg";
  CROPSIGHT_REQUIRE_DATA(grape_image);
  testing::TempDir dir;
  fs::create_directories(dir / "grapes");
  fs::copy_file(grape_image, dir / "grapes" / grape_image.filename());
  auto options = images_options(dir / "grapes");
  options.detector = "detector-grape";  // the shipped CenterNet: bunch and peduncle
  RunningStudio studio(options);
  auto client = studio.client();
  const auto info = nlohmann::json::parse(client.Get("/api/info")->body);
  EXPECT_EQ(info["model"], "detector-grape");
  EXPECT_EQ(info["classes"], nlohmann::json(nn::load_center_detector(io::find_model("detector-grape"))->class_names()));
  const auto proposals = client.Get("/api/image/0/proposals");
  ASSERT_EQ(proposals->status, 200);
  const auto shapes = nlohmann::json::parse(proposals->body)["shapes"];  // a copy: the parsed document is a temporary
  EXPECT_FALSE(shapes.empty()) << "the grape detector proposes nothing on a grape image";
  for (const auto& s : shapes) {
    EXPECT_NE(std::find(info["classes"].begin(), info["classes"].end(), s["label"]), info["classes"].end()) << s;
    ASSERT_EQ(s["box"].size(), 4u) << s;
    const double x1 = s["box"][0], y1 = s["box"][1], x2 = s["box"][2], y2 = s["box"][3];
    EXPECT_TRUE(0 <= x1 && x1 < x2 && x2 <= 1280 && 0 <= y1 && y1 < y2 && y2 <= 720) << s;
  }
}

TEST(StudioImages, ConcurrentSavesAllLandAndASecondStudioIsReadOnly) {
  testing::TempDir dir;
  const fs::path images = image_folder(dir.path());
  RunningStudio studio(images_options(images));
  RunningStudio second(images_options(images));
  EXPECT_TRUE(studio.server().writable());
  EXPECT_FALSE(second.server().writable());
  EXPECT_EQ(second.client().Post("/api/image/0/labels", kTwoShapes, "application/json")->status, 403);
  std::vector<std::thread> threads;
  std::vector<int> statuses(9);
  for (int k = 0; k < 9; ++k)
    threads.emplace_back([&, k] {
      const std::string body = R"({"shapes": [{"label": "c)" + std::to_string(k) + R"(", "box": [1, 1, 9, 9]}]})";
      statuses[std::size_t(k)] =
          studio.client().Post("/api/image/" + std::to_string(k % 3) + "/labels", body, "application/json")->status;
    });
  for (auto& t : threads) t.join();
  for (int s : statuses) EXPECT_EQ(s, 200);
  const io::LabelSet coco = io::read_coco_labels(images / studio::kImageLabelsFolder / "coco.json");
  ASSERT_EQ(coco.images.size(), 3u);
  for (const auto& im : coco.images) EXPECT_EQ(im.shapes.size(), 1u) << im.file_name;
  for (const auto& e : fs::recursive_directory_iterator(images))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

}  // namespace cropsight::studio_testing
