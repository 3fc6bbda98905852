#include "cropsight/bridge/sequence_io.hpp"

#include <optional>

#include "cropsight/io/sequence.hpp"
#include "frame_conversion.hpp"

namespace cropsight::bridge {

struct SequenceSource::Impl {
  io::SequenceReader reader;
  CameraModel camera;
};

SequenceSource::SequenceSource(const std::string& dir) {
  io::SequenceReader reader{dir};
  CameraModel camera = to_camera_model(reader.info().camera);
  impl_ = std::make_unique<Impl>(Impl{std::move(reader), std::move(camera)});
}
SequenceSource::~SequenceSource() = default;
int SequenceSource::size() const { return impl_->reader.size(); }
bool SequenceSource::has_color() const { return impl_->reader.info().has_color; }
const CameraModel& SequenceSource::camera() const { return impl_->camera; }

FrameBuffers SequenceSource::read(int index) const {
  RgbdFrame frame = impl_->reader.read(index);
  frame.labels = {};  // a robot's frames carry no truth
  return to_frame_buffers(frame);
}

struct SequenceSink::Impl {
  io::SequenceWriter writer;  // neither copyable nor movable: built in place
  Impl(const std::string& dir, const CameraIntrinsics& k, bool overwrite) : writer(dir, k, overwrite) {}
};

SequenceSink::SequenceSink(const std::string& dir, const CameraModel& camera, bool overwrite) {
  const CameraIntrinsics k = to_intrinsics(camera);
  k.validate(dir + " camera");
  impl_ = std::make_unique<Impl>(dir, k, overwrite);
}
SequenceSink::~SequenceSink() = default;
void SequenceSink::write(const FrameBuffers& frame) { impl_->writer.write(to_rgbd_frame(frame)); }
void SequenceSink::finish() { impl_->writer.finish(); }

}  // namespace cropsight::bridge
