// libFuzzer harness: the grape data set's text clouds (io::read_grape_text).
#include "cropsight/io/grape_text.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "cloud.txt");
  cropsight::fuzz::expect_error_or_success("read_grape_text", [&] { (void)cropsight::io::read_grape_text(path); });
  return 0;
}
