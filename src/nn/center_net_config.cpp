// CenterNetConfig's checks and the class-name list: plain C++, shared by the CenterNet facade
// (cropsight_nn) and the libtorch backend plugin (compiled into both).
#include <sstream>
#include <string>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/nn/center_net.hpp"

namespace cropsight::nn {

std::vector<std::string> split_class_names(const std::string& list) {
  std::vector<std::string> out;
  std::istringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    const auto b = name.find_first_not_of(" \t"), e = name.find_last_not_of(" \t");
    if (b != std::string::npos) out.push_back(name.substr(b, e - b + 1));
  }
  return out;
}

void CenterNetConfig::validate(const std::string& where) const {
  check_config(*this, where);
  if (names().empty()) throw Error(where, "'class_names' names no class");
  mask_threshold_values(where);
  if (mask_upsampling != "bilinear" && mask_upsampling != "nearest")
    throw Error(where, "'mask_upsampling' must be bilinear or nearest, not '" + mask_upsampling + "'");
  mask_input_sizes(where);
}

std::vector<std::pair<int, int>> CenterNetConfig::mask_input_sizes(const std::string& where) const {
  std::vector<std::pair<int, int>> out;
  for (const auto& item : split_class_names(mask_inputs)) {
    int w = 0, h = 0;
    char x = 0, rest = 0;
    std::istringstream in(item);
    const bool parsed = bool(in >> w >> x >> h) && (x == 'x' || x == 'X') && !(in >> rest);
    if (!parsed || w < 32 || h < 32 || w > 4096 || h > 4096 || w % 32 != 0 || h % 32 != 0)
      throw Error(where, "'mask_inputs' entry '" + item + "' is not WxH with multiples of 32 in [32, 4096]");
    out.emplace_back(w, h);
  }
  return out;
}

std::vector<float> CenterNetConfig::mask_threshold_values(const std::string& where) const {
  const std::size_t classes = names().size();
  const std::vector<std::string> items = split_class_names(mask_thresholds);
  if (items.empty()) return std::vector<float>(classes, 0.5f);
  if (items.size() != classes)
    throw Error(where, "'mask_thresholds' has " + std::to_string(items.size()) + " values for " +
                           std::to_string(classes) + " classes");
  std::vector<float> out;
  for (const auto& item : items) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !(v > 0 && v < 1))
      throw Error(where, "'mask_thresholds' value '" + item + "' is not a number in (0, 1)");
    out.push_back(float(v));
  }
  return out;
}

std::vector<std::string> CenterNetConfig::names() const { return split_class_names(class_names); }

}  // namespace cropsight::nn
