// libFuzzer harness: groundtruth.json of a sequence folder (io::read_groundtruth_json).
#include "io/sequence_text.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "groundtruth.json");
  cropsight::fuzz::expect_error_or_success("read_groundtruth_json",
                                           [&] { (void)cropsight::io::detail::read_groundtruth_json(path); });
  return 0;
}
