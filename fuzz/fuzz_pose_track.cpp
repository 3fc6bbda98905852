// libFuzzer harness: a pose file of `import --poses` (io::read_pose_track: CSV or TUM, chosen by
// content), then the track joined to frame times as import joins it.
#include "cropsight/io/pose_track.hpp"

#include <vector>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "poses.txt");
  cropsight::fuzz::expect_error_or_success("read_pose_track", [&] {
    const cropsight::io::PoseTrack track = cropsight::io::read_pose_track(path);
    const double t0 = track.poses.front().time;
    const std::vector<double> frame_times = {t0, t0 + 0.1, t0 + 1.0};
    (void)cropsight::io::join_poses(track, frame_times, 0.05, "poses.txt");
  });
  return 0;
}
