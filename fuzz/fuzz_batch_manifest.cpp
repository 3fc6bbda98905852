// libFuzzer harness: a batch manifest (batch::read_manifest): the first byte chooses the form
// (even: YAML, odd: CSV), the rest is the file. Its recordings do not exist, so every input that
// parses ends in the recording check; what is fuzzed is the parsing and checking before it.
#include "cropsight/batch/manifest.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool csv = (data[0] & 1) != 0;
  const auto path = cropsight::fuzz::write_input(data + 1, size - 1, csv ? "manifest.csv" : "manifest.yaml");
  cropsight::fuzz::expect_error_or_success("read_manifest", [&] { (void)cropsight::batch::read_manifest(path); });
  return 0;
}
