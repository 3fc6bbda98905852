// libFuzzer harness: broccoli classifier model JSON (learning::load_model: SVM or kNN, standardiser,
// recipe).
#include "cropsight/learning/model.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "model.json");
  cropsight::fuzz::expect_error_or_success("load_model", [&] { (void)cropsight::learning::load_model(path); });
  return 0;
}
