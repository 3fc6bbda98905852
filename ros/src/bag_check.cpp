#include "bag_check.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "cropsight/core/error.hpp"

namespace cropsight::ros_io::detail {

namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;
constexpr std::uint64_t kMaxChunkSize = std::uint64_t(1) << 30;

enum Op : unsigned char { kMessage = 2, kBagHeader = 3, kIndex = 4, kChunk = 5, kChunkInfo = 6, kConnection = 7 };

std::uint64_t read_le(const char* p, std::size_t n) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < n; ++i) v |= std::uint64_t(static_cast<unsigned char>(p[i])) << (8 * i);
  return v;
}

struct Record {
  std::size_t offset = 0;  // of its header length, from the start of the buffer walked
  std::map<std::string, std::string> fields;
  unsigned char op = 0;
  std::size_t data = 0, data_size = 0;  // offset and size of its data
};

class Walker {
 public:
  Walker(const std::string& bytes, const std::string& where) : b_(bytes), where_(where) {}

  [[noreturn]] void fail(std::size_t offset, const std::string& problem) const {
    throw Error(where_, "damaged ROS bag at byte " + std::to_string(offset) + ": " + problem);
  }

  // The records of [begin, end) of the buffer; `base` is added to offsets in messages.
  std::vector<Record> records(std::size_t begin, std::size_t end, std::size_t base, const char* inside) const {
    std::vector<Record> out;
    std::size_t p = begin;
    while (p < end) {
      Record r;
      r.offset = p;
      const std::size_t header_size = length_at(p, end, "record header", inside, base);
      const std::size_t h = p + 4;
      r.fields = fields(h, header_size, base, "its record header");
      const auto op = r.fields.find("op");
      if (op == r.fields.end() || op->second.size() != 1) fail(base + p, "record without a one-byte op field");
      r.op = static_cast<unsigned char>(op->second[0]);
      const std::size_t d = h + header_size;
      r.data_size = length_at(d, end, "record data", inside, base);
      r.data = d + 4;
      // A connection record's data is a header too (the topic's connection header: type,
      // md5sum, message_definition), parsed by roscpp's ros::Header, which checks a field's
      // length against 1 MB but not against the bytes left (a read past the buffer, fuzz_bag).
      if (r.op == kConnection) fields(r.data, r.data_size, base, "its connection header");
      out.push_back(r);
      p = r.data + r.data_size;
    }
    return out;
  }

  // The name=value fields, each with a 4-byte length, filling [h, h + size) exactly.
  std::map<std::string, std::string> fields(std::size_t h, std::size_t size, std::size_t base,
                                            const char* inside) const {
    std::map<std::string, std::string> out;
    std::size_t q = h;
    while (q < h + size) {
      const std::size_t field_size = length_at(q, h + size, "header field", inside, base);
      const std::string field = b_.substr(q + 4, field_size);
      const std::size_t eq = field.find('=');
      if (eq == std::string::npos) fail(base + q, "header field without '='");
      out[field.substr(0, eq)] = field.substr(eq + 1);
      q += 4 + field_size;
    }
    return out;
  }

  std::uint64_t integer(const Record& r, const char* name, std::size_t size, std::size_t base = 0) const {
    const auto f = r.fields.find(name);
    if (f == r.fields.end()) fail(base + r.offset, std::string("record without its '") + name + "' field");
    if (f->second.size() != size)
      fail(base + r.offset, std::string("field '") + name + "' holds " + std::to_string(f->second.size()) +
                                " bytes, not " + std::to_string(size));
    return read_le(f->second.data(), size);
  }

 private:
  // A 4-byte length at p followed by that many bytes, all before `end`.
  std::size_t length_at(std::size_t p, std::size_t end, const char* what, const char* inside, std::size_t base) const {
    if (end - p < 4) fail(base + p, std::string("truncated ") + what + " length");
    const std::uint64_t n = read_le(b_.data() + p, 4);
    if (n > end - p - 4)
      fail(base + p, std::string(what) + " of " + std::to_string(n) + " bytes runs past the end of " + inside);
    return std::size_t(n);
  }

  const std::string& b_;
  const std::string& where_;
};

}  // namespace

// Long on purpose: the bag records walked in file order, each length checked before it is trusted.
void check_bag(const std::string& bytes, const std::string& where) {
  if (bytes.compare(0, kMagicSize, kMagic) != 0)
    throw Error(where, "not a readable ROS bag: it does not start with '#ROSBAG V2.0' (bag format 2.0)");
  const Walker w(bytes, where);
  const std::vector<Record> top = w.records(kMagicSize, bytes.size(), 0, "the file");
  if (top.empty() || top.front().op != kBagHeader) w.fail(kMagicSize, "the first record is not the bag header");
  std::map<std::size_t, std::size_t> at;  // record offset -> index in `top`
  for (std::size_t i = 0; i < top.size(); ++i) at[top[i].offset] = i;

  // Records of each uncompressed chunk, by the chunk's index in `top` (offsets from its data).
  std::map<std::size_t, std::set<std::size_t>> chunk_records;
  std::optional<std::size_t> last_chunk;
  for (std::size_t i = 0; i < top.size(); ++i) {
    const Record& r = top[i];
    if (r.op == kChunk) {
      last_chunk = i;
      const auto c = r.fields.find("compression");
      if (c == r.fields.end()) w.fail(r.offset, "chunk without its 'compression' field");
      const std::uint64_t size = w.integer(r, "size", 4);
      if (c->second == "none") {
        if (size != r.data_size)
          w.fail(r.offset, "uncompressed chunk declares " + std::to_string(size) + " bytes but holds " +
                               std::to_string(r.data_size));
        std::set<std::size_t>& starts = chunk_records[i];
        for (const Record& inner : w.records(r.data, r.data + r.data_size, 0, "its chunk")) {
          if (inner.op != kMessage && inner.op != kConnection)
            w.fail(inner.offset, "a chunk holds a record that is neither a message nor a connection");
          starts.insert(inner.offset - r.data);
        }
      } else if (c->second == "bz2" || c->second == "lz4") {
        if (size > kMaxChunkSize)
          w.fail(r.offset, "chunk declares " + std::to_string(size) + " bytes uncompressed, more than 1 GiB");
      } else {
        w.fail(r.offset, "unknown chunk compression '" + c->second + "'");
      }
    } else if (r.op == kIndex) {
      if (w.integer(r, "ver", 4) != 1) w.fail(r.offset, "index record of a version other than 1");
      const std::uint64_t count = w.integer(r, "count", 4);
      w.integer(r, "conn", 4);
      if (count * 12 != r.data_size)
        w.fail(r.offset,
               "index record of " + std::to_string(count) + " entries holds " + std::to_string(r.data_size) + " bytes");
      if (!last_chunk) w.fail(r.offset, "index record before any chunk");
      const auto starts = chunk_records.find(*last_chunk);
      if (starts == chunk_records.end()) continue;  // a compressed chunk: rosbag checks
      for (std::uint64_t e = 0; e < count; ++e) {
        const std::uint64_t off = read_le(bytes.data() + r.data + e * 12 + 8, 4);
        if (!starts->second.count(std::size_t(off)))
          w.fail(r.offset,
                 "index entry points at offset " + std::to_string(off) + " of its chunk, where no record starts");
      }
    } else if (r.op == kChunkInfo) {
      if (w.integer(r, "ver", 4) != 1) w.fail(r.offset, "chunk info record of a version other than 1");
      const std::uint64_t pos = w.integer(r, "chunk_pos", 8);
      w.integer(r, "start_time", 8);
      w.integer(r, "end_time", 8);
      const std::uint64_t count = w.integer(r, "count", 4);
      if (count * 8 != r.data_size)
        w.fail(r.offset, "chunk info of " + std::to_string(count) + " connections holds " +
                             std::to_string(r.data_size) + " bytes");
      const auto c = at.find(std::size_t(pos));
      if (pos > bytes.size() || c == at.end() || top[c->second].op != kChunk)
        w.fail(r.offset, "chunk info points at byte " + std::to_string(pos) + ", where no chunk starts");
    } else if (r.op == kConnection) {
      w.integer(r, "conn", 4);
      if (!r.fields.count("topic")) w.fail(r.offset, "connection record without its 'topic' field");
    }
  }

  // The index section rosbag seeks to: conn_count connections, then chunk_count chunk infos.
  const Record& header = top.front();
  const std::uint64_t index_pos = w.integer(header, "index_pos", 8);
  const std::uint64_t conn_count = w.integer(header, "conn_count", 4);
  const std::uint64_t chunk_count = w.integer(header, "chunk_count", 4);
  const auto first = at.find(std::size_t(index_pos));
  if (index_pos > bytes.size() || first == at.end())
    w.fail(header.offset,
           "index_pos " + std::to_string(index_pos) +
               " is not the start of a record (an unindexed or damaged bag: `rosbag reindex` may repair it)");
  std::uint64_t connections = 0, chunk_infos = 0;
  for (std::size_t i = first->second; i < top.size(); ++i) {
    if (top[i].op == kConnection && chunk_infos == 0)
      ++connections;
    else if (top[i].op == kChunkInfo)
      ++chunk_infos;
    else
      w.fail(top[i].offset, "the index section holds a record that is neither a connection nor a chunk info");
  }
  if (connections != conn_count || chunk_infos != chunk_count)
    w.fail(header.offset, "the bag header counts " + std::to_string(conn_count) + " connections and " +
                              std::to_string(chunk_count) + " chunks; its index holds " + std::to_string(connections) +
                              " and " + std::to_string(chunk_infos));
}

namespace {

// Walks a serialised ROS message: fixed fields are skipped, each length-prefixed string or
// array must fit in what is left.
class MessageWalker {
 public:
  MessageWalker(const unsigned char* data, std::size_t size, const std::string& where, const std::string& type)
      : data_(data), size_(size), where_(where), type_(type) {}
  void skip(std::size_t n) {
    if (size_ - p_ < n) fail();
    p_ += n;
  }
  // A uint32 length followed by length items of item_size bytes; returns the length.
  std::uint64_t array(std::size_t item_size) {
    if (size_ - p_ < 4) fail();
    const std::uint64_t n = read_le(reinterpret_cast<const char*>(data_ + p_), 4);
    p_ += 4;
    if (item_size > 0 && n > (size_ - p_) / item_size) fail();
    p_ += std::size_t(n) * item_size;
    return n;
  }
  void header() {
    skip(4 + 8);  // seq, stamp
    array(1);     // frame_id
  }

 private:
  [[noreturn]] void fail() const {
    throw Error(where_, "damaged " + type_ + " message in the bag: a length runs past the message's " +
                            std::to_string(size_) + " bytes");
  }
  const unsigned char* data_;
  std::size_t size_, p_ = 0;
  const std::string& where_;
  const std::string& type_;
};

}  // namespace

void check_message(const std::string& type, const unsigned char* data, std::size_t size, const std::string& where) {
  MessageWalker w(data, size, where, type);
  if (type == "sensor_msgs/Image") {
    w.header();
    w.skip(8);      // height, width
    w.array(1);     // encoding
    w.skip(1 + 4);  // is_bigendian, step
    w.array(1);     // data
  } else if (type == "sensor_msgs/CameraInfo") {
    w.header();
    w.skip(8);                          // height, width
    w.array(1);                         // distortion_model
    w.array(8);                         // D
    w.skip(8 * (9 + 9 + 12) + 8 + 17);  // K, R, P, binning, roi
  } else if (type == "tf2_msgs/TFMessage") {
    const std::uint64_t n = w.array(0);
    for (std::uint64_t i = 0; i < n; ++i) {
      w.header();
      w.array(1);     // child_frame_id
      w.skip(7 * 8);  // translation, rotation
    }
  }
}

void check_bag_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open for reading");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path, "read error");
  check_bag(bytes, path);
}

}  // namespace cropsight::ros_io::detail
