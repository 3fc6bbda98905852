// Writes the fuzzers' seed corpora (fuzz/corpus/<name>/) with the library's own writers, so the
// seeds are files the product really produces, kept small (a few frames, tiny models) because
// libFuzzer's default input limit is the largest seed. Run once by hand and committed:
//   build-fuzz/bin/fuzz_make_seeds fuzz/corpus
// (scripts/fuzz.sh explains; the ONNX YOLOv5/SSD seeds come from tests/nn/make_onnx_fixtures.py.)
// Needs the libtorch plugin for the network seeds ($CROPSIGHT_NN_BACKEND).
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/io/voc.hpp"
#include "cropsight/learning/gbdt.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "cropsight/tracking/field_map_io.hpp"

namespace fs = std::filesystem;
using namespace cropsight;

namespace {

fs::path seed(const fs::path& root, const std::string& harness, const std::string& file) {
  fs::create_directories(root / harness);
  return root / harness / file;
}

void write_text(const fs::path& path, const std::string& text) { io::write_file_atomic(path, text); }

// camera.yaml, poses.csv, groundtruth.json and the frames' images from a two-frame sequence.
void sequence_seeds(const fs::path& root) {
  CameraIntrinsics cam;
  cam.width = 8, cam.height = 6, cam.fx = cam.fy = 10.0, cam.cx = 4.0, cam.cy = 3.0, cam.sensor = "kinect-v2";
  cam.distortion = {0.1, -0.05, 0.0, 0.0, 0.01};
  const fs::path dir = fs::temp_directory_path() / "cropsight-fuzz-seeds-sequence";
  fs::remove_all(dir);
  {
    io::SequenceWriter w(dir, cam);
    for (int i = 0; i < 2; ++i) {
      RgbdFrame f;
      f.index = i, f.timestamp = 0.1 * i, f.camera = cam;
      f.depth = DepthImage(8, 6, std::uint16_t(1200 + i));
      f.color = ColorImage(8, 6, Rgb8{40, 120, 30});
      f.labels = LabelImage(8, 6, 0);
      f.labels.at(3, 2) = 1;
      f.camera_position = Eigen::Vector3d(0.0, 0.05 * i, 1.2);
      w.write(f);
    }
    io::GroundTruth truth;
    io::InstanceTruth head;
    head.id = 1, head.position = {0.0, 0.0, 1.1}, head.diameter_mm = 120.0, head.extra["height_m"] = 0.3;
    truth.instances.push_back(head);
    w.set_groundtruth(truth);
    w.finish();
  }
  fs::copy_file(dir / "camera.yaml", seed(root, "camera_yaml", "camera.yaml"), fs::copy_options::overwrite_existing);
  // camera_yaml also reads ROS camera_info YAMLs, in both spellings.
  write_text(seed(root, "camera_yaml", "camera_info.yaml"),
             "image_width: 8\nimage_height: 6\ncamera_name: ir\ncamera_matrix:\n  rows: 3\n  cols: 3\n  data: [7, 0, "
             "3.5, 0, 7, 2.5, 0, 0, 1]\ndistortion_model: plumb_bob\ndistortion_coefficients:\n  rows: 1\n  cols: 5\n"
             "  data: [0.1, -0.2, 0, 0, 0.05]\n");
  write_text(seed(root, "camera_yaml", "camera_info_echo.yaml"),
             "height: 6\nwidth: 8\ndistortion_model: \"plumb_bob\"\nD: [0.0, 0.0, 0.0, 0.0, 0.0]\nK: [7.0, 0.0, 3.5, "
             "0.0, 7.0, 2.5, 0.0, 0.0, 1.0]\n---\n");
  write_text(seed(root, "pose_track", "odometry.csv"),
             "t,x,y,z,qx,qy,qz,qw,speed\n10.0,0,0,1,0,0,0,1,0.2\n10.1,0.02,0,1,0,0,0,1,0.2\n");
  write_text(seed(root, "pose_track", "trajectory.tum"),
             "# t x y z qx qy qz qw\n10.0 0 0 1 0 0 0 1\n10.2 0.04 0 1 0 0 0.0998 0.995\n");
  write_text(seed(root, "extrinsics_yaml", "extrinsics.yaml"),
             "depth_to_color:\n  rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n  translation: [0.052, 0, 0.001]\n");
  // poses_csv: the first byte is the frame count the rows must match.
  write_text(seed(root, "poses_csv", "poses.csv"), std::string(1, '\x02') + io::read_file(dir / "poses.csv"));
  fs::copy_file(dir / "groundtruth.json", seed(root, "groundtruth_json", "groundtruth.json"),
                fs::copy_options::overwrite_existing);
  // sequence_images: the first byte (modulo 3) picks depth (0), colour (1) or labels (2).
  const std::pair<const char*, char> images[] = {{"depth", '\0'}, {"color", '\1'}, {"labels", '\2'}};
  for (const auto& [name, pick] : images) {
    write_text(seed(root, "sequence_images", std::string(name) + ".bin"),
               std::string(1, pick) + io::read_file(dir / name / "000000.png"));
  }
  fs::remove_all(dir);
}

void cloud_seeds(const fs::path& root) {
  OrganizedCloud organised(4, 3);
  for (int v = 0; v < 3; ++v) {
    for (int u = 0; u < 4; ++u) {
      const int i = organised.index(u, v);
      organised.x[i] = 0.01f * u, organised.y[i] = 0.01f * v, organised.z[i] = 1.0f + 0.001f * u;
    }
  }
  io::write_cloud(seed(root, "pcd", "organised_binary.pcd"), organised, true);
  io::write_cloud(seed(root, "pcd", "organised_ascii.pcd"), organised, false);
  Cloud cloud;
  for (int i = 0; i < 5; ++i) {
    cloud.points.emplace_back(0.1f * i, 0.2f, 0.3f);
    cloud.colors.emplace_back(0.2f * i, 0.3f, 0.1f);
    cloud.labels.push_back(i % 2);
  }
  io::write_cloud(seed(root, "pcd", "cloud_binary.pcd"), cloud, true);
  io::write_cloud(seed(root, "pcd", "cloud_ascii.pcd"), cloud, false);
  io::write_cloud(seed(root, "ply", "cloud_binary.ply"), cloud, true);
  io::write_cloud(seed(root, "ply", "cloud_ascii.ply"), cloud, false);
  io::write_grape_text(seed(root, "grape_text", "cloud.txt"), cloud);
}

void annotation_seeds(const fs::path& root) {
  write_text(seed(root, "voc_xml", "a.xml"),
             "<annotation><filename>a.png</filename><size><width>16</width><height>12</height><depth>3</depth>"
             "</size><object><name>potato</name><difficult>0</difficult><bndbox><xmin>2</xmin><ymin>3</ymin>"
             "<xmax>10</xmax><ymax>9</ymax></bndbox></object></annotation>\n");
  write_text(seed(root, "coco_json", "annotations.json"),
             R"({"images": [{"id": 1, "file_name": "a.png", "width": 16, "height": 12}],
 "categories": [{"id": 1, "name": "bunch"}, {"id": 2, "name": "peduncle"}],
 "annotations": [{"id": 1, "image_id": 1, "category_id": 1, "bbox": [2, 3, 8, 6], "area": 48, "iscrowd": 0,
   "segmentation": [[2, 3, 10, 3, 10, 9, 2, 9]]},
  {"id": 2, "image_id": 1, "category_id": 2, "bbox": [5, 1, 2, 2], "area": 4, "iscrowd": 0,
   "segmentation": [[5, 1, 7, 1, 7, 3, 5, 3]]}]}
)");
  std::vector<Detection2D> dets(2);
  dets[0].x1 = 2, dets[0].y1 = 3, dets[0].x2 = 10, dets[0].y2 = 9, dets[0].score = 0.9f, dets[0].class_id = 0;
  dets[1].x1 = 5, dets[1].y1 = 1, dets[1].x2 = 7, dets[1].y2 = 3, dets[1].score = 0.4f, dets[1].class_id = 1;
  io::write_detection_text(seed(root, "detection_text", "boxes.txt"), dets, {"bunch", "peduncle"});
}

void stereo_seeds(const fs::path& root) {
  stereo::StereoCalibration c;
  c.width = 64, c.height = 48;
  c.K1 << 50, 0, 32, 0, 50, 24, 0, 0, 1;
  c.K2 = c.K1;
  c.D1 = {0.01, 0, 0, 0, 0}, c.D2 = c.D1;
  c.T = Eigen::Vector3d(-0.06, 0, 0);
  c.rms = 0.3, c.views = 12;
  stereo::save_calibration(seed(root, "stereo_calibration", "calibration.yaml"), c);
  Image<float> gt(6, 4, 12.5f);
  gt.at(1, 1) = std::numeric_limits<float>::infinity();
  stereo::write_pfm(seed(root, "stereo_ground_truth", "disp.pfm"), gt);
  Image<std::uint16_t> png(6, 4, 3200);
  write_text(seed(root, "stereo_ground_truth", "disp16.png"), io::encode_png(png));
  write_text(seed(root, "stereo_ground_truth", "disp8.png"), io::encode_png(GrayImage(6, 4, 40)));
}

void model_seeds(const fs::path& root) {
  learning::Dataset data(3);
  for (int i = 0; i < 12; ++i) {
    data.values.insert(data.values.end(), {float(i % 2), 0.1f * i, 1.0f - 0.05f * i});
    data.labels.push_back(i % 2);
  }
  learning::ModelInfo info;
  info.task = "broccoli-heads", info.pipeline = "oes", info.features = {"geometric"}, info.feature_dim = 3;
  info.config = {{"detection.min_points", "40"}};
  for (const char* type : {"svm-rbf", "svm-linear", "knn"}) {
    learning::ClassifierParams params;
    params.type = type;
    params.knn_k = 3;
    learning::save_model(seed(root, "broccoli_model", std::string(type) + ".json"),
                         learning::train_model(data, params, info));
  }
  learning::GbdtParams gp;
  gp.rounds = 2, gp.max_depth = 2, gp.num_class = 2, gp.nthread = 1;
  learning::Gbdt gbdt;
  std::vector<float> labels(data.labels.begin(), data.labels.end());
  gbdt.train(data.values, data.size(), 3, labels, {}, gp);
  gbdt.set_attribute("recipe", "xyz");
  gbdt.save(seed(root, "gbdt_model", "model.json"));

  std::vector<tracking::TrackedHead> heads(2);
  heads[0].id = 1, heads[0].position = {0.1, 2.0, 0.0}, heads[0].frames_seen = 5, heads[0].diameter_mm = 120;
  heads[1].id = 2, heads[1].position = {0.0, 2.5, 0.0}, heads[1].frames_seen = 3, heads[1].harvestable = true;
  tracking::write_field_map(seed(root, "field_map", "map.csv"), heads);
}

void network_seeds(const fs::path& root) {
  nn::PointNetConfig pc;
  pc.num_points = 64, pc.sa1_points = 16, pc.sa2_points = 8, pc.sa3_points = 4, pc.k1 = pc.k2 = pc.k3 = 4;
  pc.width = 4, pc.threads = 1;
  nn::PointSegmenter(pc).save(seed(root, "network_archive", "segmenter.pt"));
  nn::CenterNetConfig cc;
  cc.class_names = "bunch,peduncle", cc.input_width = cc.input_height = 32, cc.width = 4;
  const nn::CenterNet net(cc);
  net.save(seed(root, "network_archive", "detector.pt"));
  net.export_onnx(seed(root, "onnx_model", "centernet.onnx"));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
    return 2;
  }
  const fs::path root = argv[1];
  try {
    sequence_seeds(root);
    cloud_seeds(root);
    annotation_seeds(root);
    stereo_seeds(root);
    model_seeds(root);
    network_seeds(root);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
