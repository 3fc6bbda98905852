// CenterNetConfig's checks and the class-name list: plain C++, shared by the CenterNet facade
// (cropsight_nn) and the libtorch backend plugin (compiled into both).
#include <sstream>

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
}

std::vector<std::string> CenterNetConfig::names() const { return split_class_names(class_names); }

}  // namespace cropsight::nn
