// libFuzzer harness: field maps of `detect broccoli --map` (tracking::read_field_map).
#include "cropsight/tracking/field_map_io.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "map.csv");
  cropsight::fuzz::expect_error_or_success("read_field_map", [&] { (void)cropsight::tracking::read_field_map(path); });
  return 0;
}
