// Labelled grape clouds (see truth.hpp).
#include "cropsight/pipeline/grape/truth.hpp"

#include "cropsight/io/grape_text.hpp"

namespace cropsight::pipeline::grape {

std::vector<Cloud> load_grape_clouds(const std::vector<std::filesystem::path>& files) {
  std::vector<Cloud> out;
  out.reserve(files.size());
  for (const auto& f : files) out.push_back(io::read_grape_text(f));
  return out;
}

}  // namespace cropsight::pipeline::grape
