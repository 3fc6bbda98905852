#pragma once
// The labels a studio writes into a depth sequence, in the format `train broccoli` reads
// (docs/formats.md): one 16-bit instance PNG per labelled frame in SEQ/labels/ (0 = not a head,
// k = head k), SEQ/labelled.csv listing the labelled frames (the others have no labels yet and
// training skips them), and one SEQ/groundtruth.json instance per labelled head.
//
// Every file is written under a temporary name and renamed (io/files.hpp), label image first, so
// a kill leaves either the old or the new frame. labels/ is the truth: labelled.csv is written
// before the first image and rebuilt from labels/ when a studio opens the sequence (reconcile),
// so a kill between the renames heals at the next start (the
// frame's groundtruth.json entries at its next save; training reads only the images). Instances
// other tools wrote into groundtruth.json are kept; a frame's own instances (extra key
// "studio_frame") are replaced when it is saved again. Ids are unique over the sequence; the
// studio does not know which heads of two frames are one plant, so each labelled head is its own.
//
// Thread-safe: saves are serialised by a mutex (the server answers requests on several threads).
#include <filesystem>
#include <mutex>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/core/rgbd_frame.hpp"

namespace cropsight::studio {

/// One labelled head: its pixel indices (row-major, y·width + x) in the frame.
using HeadPixels = std::vector<int>;

class LabelStore {
 public:
  /// The labels of `sequence` (frames of `frames` depth images). Throws nothing.
  LabelStore(std::filesystem::path sequence, const CameraIntrinsics& camera, int frames, bool read_only);
  /// Rewrites labelled.csv from labels/ when the sequence has one (a writer killed between a
  /// label image and the list); call before reading the sequence, holding its lock. Returns
  /// whether it rewrote. Throws Error naming the file it cannot write.
  static bool reconcile(const std::filesystem::path& sequence);

  /// Labelled frames, ascending.
  std::vector<int> labelled() const;
  /// The label image of `frame`, empty when the frame is not labelled.
  LabelImage labels(int frame) const;
  /// Writes `frame`'s heads (later heads win where two overlap; empty heads are dropped), then
  /// labelled.csv and groundtruth.json. `depth` (the frame's raw depth) gives each head's centroid
  /// and diameter. Throws Error when read-only or on a write failure; nothing is half written.
  void save(int frame, const std::vector<HeadPixels>& heads, const DepthImage& depth);

 private:
  void write_index_files(int changed_frame, const std::vector<HeadPixels>& heads, const LabelImage& image,
                         const DepthImage& depth);

  std::filesystem::path dir_;
  CameraIntrinsics camera_;
  int frames_ = 0;
  bool read_only_ = false;
  mutable std::mutex mutex_;
};

}  // namespace cropsight::studio
