// libFuzzer harness: preset YAML and --set values, through the path every command
// takes: io::load_preset_with_overrides, then each pipeline's configuration applied and
// validated (broccoli, potato, seedling, grape, the broccoli simulator). The input's first line
// holds the --set values, separated by ';'; the rest is the YAML file.
#include <string>
#include <vector>

#include "cropsight/io/config_yaml.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/grape/pipeline.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"
#include "cropsight/pipeline/seedling/config.hpp"
#include "cropsight/sim/broccoli/broccoli_config.hpp"
#include "fuzz_support.hpp"

namespace {

std::vector<std::string> split_sets(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= line.size()) {
    const std::size_t end = std::min(line.find(';', start), line.size());
    if (end > start) out.push_back(line.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

template <typename Config>
void apply_and_validate(const char* what, const cropsight::ConfigMap& map) {
  cropsight::fuzz::expect_error_or_success(what, [&] {
    Config cfg;
    cropsight::apply_config(cfg, map, "preset");
    cfg.validate("preset");
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t eol = input.find('\n');
  const std::string first = input.substr(0, eol);
  const std::string yaml = eol == std::string::npos ? std::string() : input.substr(eol + 1);
  const auto path = cropsight::fuzz::write_input(yaml, "preset.yaml");
  const std::vector<std::string> sets = split_sets(first);

  cropsight::ConfigMap map;
  bool loaded = false;
  cropsight::fuzz::expect_error_or_success("load_preset_with_overrides", [&] {
    map = cropsight::io::load_preset_with_overrides(path.string(), sets);
    loaded = true;
  });
  if (!loaded) return 0;
  apply_and_validate<cropsight::pipeline::broccoli::Config>("broccoli", map);
  apply_and_validate<cropsight::pipeline::grape::Config>("grape", map);
  apply_and_validate<cropsight::sim::BroccoliSimConfig>("broccoli simulator", map);
  cropsight::fuzz::expect_error_or_success(
      "potato", [&] { (void)cropsight::pipeline::potato::load_config(path.string(), cropsight::ConfigMap{}); });
  cropsight::fuzz::expect_error_or_success("seedling",
                                           [&] { (void)cropsight::pipeline::seedling::load_config(path.string()); });
  return 0;
}
