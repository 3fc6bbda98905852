#include "cropsight/report/sequence_summary.hpp"

#include <algorithm>
#include <limits>
#include <set>

namespace cropsight::report {

SequenceSummary summarize_sequence(const io::SequenceReader& reader) {
  SequenceSummary s;
  s.info = reader.info();
  s.instances = int(reader.groundtruth().instances.size());
  std::uint16_t dmin = std::numeric_limits<std::uint16_t>::max(), dmax = 0;
  double valid_sum = 0.0, labelled_sum = 0.0;
  for (int i = 0; i < reader.size(); ++i) {
    const RgbdFrame f = reader.read(i);
    std::size_t valid = 0;
    for (std::uint16_t d : f.depth.data) {
      if (d == 0) continue;
      ++valid;
      dmin = std::min(dmin, d);
      dmax = std::max(dmax, d);
    }
    const double n = double(f.depth.size());
    s.valid_depth_per_frame.push_back(double(valid) / n);
    valid_sum += double(valid) / n;
    if (!f.labels.empty()) {
      std::set<std::uint16_t> ids;
      std::size_t labelled = 0;
      for (std::uint16_t l : f.labels.data)
        if (l != 0) {
          ++labelled;
          ids.insert(l);
        }
      labelled_sum += double(labelled) / n;
      s.visible_instances_per_frame.push_back(int(ids.size()));
    }
  }
  const double frames = std::max(1, reader.size());
  s.valid_depth_fraction = valid_sum / frames;
  s.labelled_fraction = labelled_sum / frames;
  if (dmax > 0) {
    s.depth_min_m = dmin * s.info.camera.depth_scale;
    s.depth_max_m = dmax * s.info.camera.depth_scale;
  }
  return s;
}

}  // namespace cropsight::report
