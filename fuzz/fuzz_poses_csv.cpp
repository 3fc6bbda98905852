// libFuzzer harness: poses.csv of a sequence folder (io::read_poses_csv), checked
// against a frame count taken from the input's first byte (modulo 65), as the sequence reader
// checks it against its depth frames; the rest of the input is the file.
#include <string_view>

#include "fuzz_support.hpp"
#include "io/sequence_text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int frames = data[0] % 65;
  const auto path = cropsight::fuzz::write_input(data + 1, size - 1, "poses.csv");
  cropsight::fuzz::expect_error_or_success("read_poses_csv",
                                           [&] { (void)cropsight::io::detail::read_poses_csv(path, frames); });
  return 0;
}
