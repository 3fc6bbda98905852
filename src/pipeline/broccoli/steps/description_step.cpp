#include "cropsight/pipeline/broccoli/steps/description_step.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace cropsight::pipeline::broccoli::steps {

DescriptionStep::DescriptionStep(const std::string& features, features::FeatureConfig options, int min_normal_points,
                                 int oversized_above)
    : feature_set_(features::FeatureSet::parse(features, "config")),
      options_(std::move(options)),
      min_normal_points_(min_normal_points),
      oversized_above_(oversized_above) {}

void DescriptionStep::run(std::vector<Segment>& segments, const OrganizedCloud& cloud, CandidatePool& pool,
                          StageTimer& timer) const {
  pool.reset(segments.size());
  auto t = timer.scope("features");
  for (std::size_t k = 0; k < segments.size(); ++k) {
    Candidate& c = pool[k];
    c.proposed = false;
    std::swap(c.segment, segments[k]);  // keeps the slot's old index buffer in `segments`
    // The organised clusterings return ascending indices already; FEC's are sorted here.
    if (!std::is_sorted(c.segment.indices.begin(), c.segment.indices.end()))
      std::sort(c.segment.indices.begin(), c.segment.indices.end());
    c.oversized = oversized_above_ > 0 && int(c.segment.size()) > oversized_above_;
    if (c.oversized) {
      c.described = false;  // never a head: the lowest score, and only the split looks inside it
      c.normal_points = -1;
      continue;
    }
    describe(cloud, c);
  }
}

void DescriptionStep::describe(const OrganizedCloud& cloud, Candidate& c) const {
  feature_set_.compute(cloud, c.segment.indices, options_, c.features);
  c.normal_points = -1;  // not counted unless min_normal_points asks for it
  c.described = true;
  if (min_normal_points_ > 0) {
    int with_normal = 0;
    for (int i : c.segment.indices) with_normal += std::isfinite(cloud.nx[std::size_t(i)]) ? 1 : 0;
    c.normal_points = with_normal;
    c.described = with_normal >= min_normal_points_;
  }
}

}  // namespace cropsight::pipeline::broccoli::steps
