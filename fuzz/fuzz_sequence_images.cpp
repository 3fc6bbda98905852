// libFuzzer harness: a sequence folder's images as the sequence reader reads them.
// A valid one-frame sequence (8 x 6, depth + colour + labels) is written once; for each input,
// the first byte (modulo 3) picks which of depth/, color/ or labels/ 000000.png gets the remaining bytes,
// then io::SequenceReader opens the folder and reads frame 0 (bit depth, channels and size
// checks; OpenCV's decoders behind them).
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "fuzz_support.hpp"

namespace {

constexpr int kWidth = 8, kHeight = 6;

struct ValidImages {
  std::string depth, color, labels;
  ValidImages() {
    cropsight::DepthImage depth_img(kWidth, kHeight, 1200);
    cropsight::ColorImage color_img(kWidth, kHeight, cropsight::Rgb8{40, 120, 30});
    cropsight::LabelImage labels_img(kWidth, kHeight, 0);
    labels_img.at(3, 2) = 1;
    depth = cropsight::io::encode_png(depth_img);
    color = cropsight::io::encode_png(color_img);
    labels = cropsight::io::encode_png(labels_img);
  }
};

void write_sequence(const ValidImages& valid) {
  cropsight::CameraIntrinsics cam;
  cam.width = kWidth, cam.height = kHeight, cam.fx = cam.fy = 10.0, cam.cx = 4.0, cam.cy = 3.0;
  cropsight::io::write_camera_yaml(cropsight::fuzz::scratch_dir() / "seq" / "camera.yaml", cam);
  cropsight::fuzz::write_input(valid.depth, "seq/depth/000000.png");
  cropsight::fuzz::write_input(valid.color, "seq/color/000000.png");
  cropsight::fuzz::write_input(valid.labels, "seq/labels/000000.png");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ValidImages valid;  // encoded once per process
  if (size == 0) return 0;
  const int which = data[0] % 3;
  std::filesystem::create_directories(cropsight::fuzz::scratch_dir() / "seq");
  write_sequence(valid);
  const char* names[] = {"seq/depth/000000.png", "seq/color/000000.png", "seq/labels/000000.png"};
  cropsight::fuzz::write_input(data + 1, size - 1, names[which]);
  cropsight::fuzz::expect_error_or_success("SequenceReader", [&] {
    const cropsight::io::SequenceReader reader(cropsight::fuzz::scratch_dir() / "seq");
    (void)reader.read(0);
  });
  return 0;
}
