// libFuzzer harness: GBDT models in XGBoost's JSON format (learning::Gbdt::load: XGBoost's loader
// behind our checks).
#include "cropsight/learning/gbdt.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "model.json");
  cropsight::fuzz::expect_error_or_success("Gbdt::load", [&] { (void)cropsight::learning::Gbdt::load(path, 1); });
  return 0;
}
