// libFuzzer harness: the depth-to-colour extrinsics YAML of `import --extrinsics`
// (io::read_extrinsics_yaml).
#include "cropsight/io/color_registration.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "extrinsics.yaml");
  cropsight::fuzz::expect_error_or_success("read_extrinsics_yaml",
                                           [&] { (void)cropsight::io::read_extrinsics_yaml(path); });
  return 0;
}
