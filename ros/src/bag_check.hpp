#pragma once
// Internal: a ROS bag's record structure checked before rosbag reads it. rosbag (Debian's
// librosbag-storage 1.15) trusts the lengths a bag declares: a record header length of 4 GB read
// from a damaged connection record made it allocate 4 GB (fuzz_bag; fuzz/regressions/bag/). The
// walk checks the format 2.0 framing rosbag relies on, so a truncated or damaged bag is an Error
// naming the file and the offset instead of an out-of-memory kill or a read past a buffer:
// - every record (length-prefixed header of name=value fields, length-prefixed data) lies inside
//   the file, and every record inside an uncompressed chunk inside its chunk; a connection
//   record's data (its connection header) is name=value fields that fill it exactly;
// - the bag header's index_pos, and each chunk info's chunk_pos, point at a record (a chunk);
//   the index section holds the connection and chunk info records the bag header counts;
// - an uncompressed chunk's declared size is its data's; a compressed one declares at most 1 GiB
//   (rosbag's default chunks are 768 kB);
// - an index record's entries (12 bytes each) point at records of the chunk before it (for an
//   uncompressed chunk; a compressed chunk's offsets are left to rosbag).
// This catches damage, not a bag crafted to pass the checks. C++17 (the ROS glue's standard).
#include <cstddef>
#include <string>

namespace cropsight::ros_io::detail {

/// Throws Error(where, ...) naming the first problem of the bag file contents `bytes`.
void check_bag(const std::string& bytes, const std::string& where);

/// Checks that every string and array length in a serialised message of `type` (only
/// "sensor_msgs/Image", "sensor_msgs/CameraInfo" and "tf2_msgs/TFMessage", the types the bag
/// importer reads; others pass) fits in its `size` bytes: roscpp's deserialiser resizes a vector
/// to the length it reads before checking the bytes are there (a 14 GB CameraInfo D, fuzz_bag).
void check_message(const std::string& type, const unsigned char* data, std::size_t size, const std::string& where);

/// Reads the file at `path` and runs check_bag on it (Error when it cannot be read).
void check_bag_file(const std::string& path);

}  // namespace cropsight::ros_io::detail
