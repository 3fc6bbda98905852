// Labelled grape clouds (see truth.hpp).
#include "cropsight/pipeline/grape/truth.hpp"

#include "cropsight/pipeline/grape/cloud_files.hpp"

namespace cropsight::pipeline::grape {

std::vector<long> label_counts(const Cloud& cloud) {
  std::vector<long> counts(6, 0);
  for (int l : cloud.labels)
    if (l >= 0 && l < 6) ++counts[std::size_t(l)];
  return counts;
}

std::vector<Cloud> load_grape_clouds(const std::vector<std::filesystem::path>& files) {
  std::vector<Cloud> out;
  out.reserve(files.size());
  for (const auto& f : files) out.push_back(read_labelled_cloud(f));
  return out;
}

}  // namespace cropsight::pipeline::grape
