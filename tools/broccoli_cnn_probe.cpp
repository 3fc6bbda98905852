// Experiment: how far a depth CNN (CenterNet with masks, trained on frames exported by
// broccoli_depth_coco) reaches where OES misses, on validation sequences.
//
//   broccoli_cnn_probe MODEL.json seq[,seq] CNN.pt|.onnx [key=value ...]
//
// Per frame: the OES detector (the model's configuration) and the CNN on the encoded depth frame.
// A CNN instance = the pixels of its box that its class mask covers and that hold a point of the
// detector's cloud (the depth window), scored by the box's score. Prints, over the sequences:
//   - AP50 over visible heads (visible_truth_points; smaller heads are ignore regions) of OES,
//     of the CNN instances alone, and of the union (CNN instances that overlap no accepted OES
//     head by more than IoU 0.3 added, scores shifted below every OES head: an upper bound for
//     "OES first, the CNN where OES found nothing");
//   - the visible heads OES misses (no accepted detection at IoU >= 0.5) and how many of them a
//     CNN instance reaches (IoU >= 0.5), and CNN instances above score 0.3 that match no head.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "broccoli_probe_args.hpp"
#include "cropsight/eval/detection_ap.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/nn/center_decode.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "cropsight/pipeline/broccoli/depth_encoding.hpp"
#include "cropsight/pipeline/broccoli/truth.hpp"

using namespace cropsight;

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: broccoli_cnn_probe MODEL.json seq[,seq] CNN.pt|.onnx [key=value ...]\n");
    return 2;
  }
  const std::string cnn_path = argv[3];
  for (int i = 3; i + 1 < argc; ++i) argv[i] = argv[i + 1];  // the shared parser reads key=value from argv[3]
  auto args = tools::parse_probe_args("broccoli_cnn_probe", argc - 1, argv);
  if (!args) return 2;
  pipeline::broccoli::Detector det(args->config);
  det.set_model(args->model);
  auto cnn = nn::load_center_detector(cnn_path, 1);
  auto* onnx = dynamic_cast<nn::CenterNetOnnx*>(cnn.get());
  auto* torch = dynamic_cast<nn::CenterNet*>(cnn.get());
  const nn::CenterNetConfig& ccfg = nn::center_net_config(*cnn, "cnn");
  const int visible = 300;
  eval::DetectionApAccumulator ap_oes, ap_cnn, ap_union;
  long missed = 0, reached = 0, cnn_false = 0, cnn_inst = 0, truth_visible = 0;
  std::vector<pipeline::broccoli::TruthInstance> truth;
  for (const std::string& dir : args->sequences) {
    const io::SequenceReader seq(dir);
    for (int f = 0; f < seq.size(); ++f) {
      const RgbdFrame frame = seq.read(f);
      det.process(frame);
      const std::vector<Detection> dets = det.detections();
      pipeline::broccoli::truth_instances(det.cloud(), 0, truth);
      std::vector<std::vector<int>> tsets;
      std::vector<bool> small;
      for (const auto& t : truth) tsets.push_back(t.indices), small.push_back(int(t.indices.size()) < visible);
      // CNN instances.
      const ColorImage img = pipeline::broccoli::encode_depth_for_cnn(frame.depth, frame.camera.depth_scale);
      const nn::CenterNetHeads heads = onnx ? onnx->heads(img) : torch->heads(img);
      const std::vector<Detection2D> boxes = nn::boxes_from_heads(heads, ccfg, img.width, img.height);
      const std::vector<GrayImage> masks = nn::masks_from_heads(heads, ccfg, img.width, img.height);
      std::vector<std::vector<int>> inst;
      std::vector<float> inst_score;
      for (const Detection2D& b : boxes) {
        std::vector<int> px = pipeline::broccoli::mask_points_in_box(b, masks[std::size_t(b.class_id)], det.cloud().z);
        if (px.size() < 30) continue;
        inst.push_back(std::move(px));
        inst_score.push_back(b.score);
      }
      std::vector<eval::DetectionApAccumulator::Scored> s_oes, s_cnn, s_union;
      for (const Detection& d : dets)
        s_oes.push_back({d.score, d.indices}), s_union.push_back({d.score + 100.0f, d.indices});
      for (std::size_t i = 0; i < inst.size(); ++i) {
        s_cnn.push_back({inst_score[i], inst[i]});
        double best = 0;
        for (const Detection& d : dets) best = std::max(best, eval::point_set_iou(inst[i], d.indices));
        if (best <= 0.3) s_union.push_back({inst_score[i], inst[i]});
        if (inst_score[i] >= 0.3) {
          ++cnn_inst;
          double bt = 0;
          for (const auto& t : tsets) bt = std::max(bt, eval::point_set_iou(t, inst[i]));
          cnn_false += bt < 0.5;
        }
      }
      ap_oes.add_frame(tsets, s_oes, small);
      ap_cnn.add_frame(tsets, s_cnn, small);
      ap_union.add_frame(tsets, s_union, small);
      for (std::size_t t = 0; t < tsets.size(); ++t) {
        if (small[t]) continue;
        ++truth_visible;
        double bo = 0, bc = 0;
        for (const Detection& d : dets) bo = std::max(bo, eval::point_set_iou(tsets[t], d.indices));
        if (bo >= 0.5) continue;
        ++missed;
        for (const auto& p : inst) bc = std::max(bc, eval::point_set_iou(tsets[t], p));
        reached += bc >= 0.5;
      }
    }
    std::fprintf(stderr, "%s done\n", dir.c_str());
  }
  std::printf("visible heads %ld; AP50 visible: OES %.3f, CNN %.3f, union %.3f\n", truth_visible, ap_oes.ap(0.5),
              ap_cnn.ap(0.5), ap_union.ap(0.5));
  std::printf(
      "OES misses %ld visible heads; a CNN instance reaches %ld of them; CNN instances >= 0.3: %ld, %ld on no head\n",
      missed, reached, cnn_inst, cnn_false);
  return 0;
}
