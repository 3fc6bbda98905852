// libFuzzer harness: per-image detection text files (io::read_detection_text: the grape ROI's
// box files and `detect objects`' text output).
#include "cropsight/io/voc.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "boxes.txt");
  cropsight::fuzz::expect_error_or_success("read_detection_text",
                                           [&] { (void)cropsight::io::read_detection_text(path); });
  return 0;
}
