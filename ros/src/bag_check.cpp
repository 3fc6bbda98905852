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

// The bytes walked: a string in memory (the fuzz harness), or the bag file itself, read a record
// header at a time so that checking a bag of any length takes a few kilobytes, never the bag.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual std::size_t size() const = 0;
  /// The n bytes at `offset` (the caller has checked they lie inside).
  virtual std::string read(std::size_t offset, std::size_t n) const = 0;
};

class StringSource : public ByteSource {
 public:
  explicit StringSource(const std::string& bytes) : b_(bytes) {}
  std::size_t size() const override { return b_.size(); }
  std::string read(std::size_t offset, std::size_t n) const override { return b_.substr(offset, n); }

 private:
  const std::string& b_;
};

class FileSource : public ByteSource {
 public:
  explicit FileSource(const std::string& path) : in_(path, std::ios::binary), path_(path) {
    if (!in_) throw Error(path, "cannot open for reading");
    in_.seekg(0, std::ios::end);
    size_ = std::size_t(in_.tellg());
  }
  std::size_t size() const override { return size_; }
  std::string read(std::size_t offset, std::size_t n) const override {
    std::string out(n, '\0');
    in_.seekg(std::streamoff(offset));
    in_.read(out.data(), std::streamsize(n));
    if (!in_) throw Error(path_, "read error at byte " + std::to_string(offset));
    return out;
  }

 private:
  mutable std::ifstream in_;
  std::string path_;
  std::size_t size_ = 0;
};

// A record header or connection header larger than this is damage: rosbag's are a few hundred
// bytes (a connection's message definition a few kilobytes), and the walk reads each into memory.
constexpr std::size_t kMaxHeaderSize = std::size_t(64) << 20;

struct Record {
  std::size_t offset = 0;  // of its header length, from the start of the bytes walked
  std::map<std::string, std::string> fields;
  unsigned char op = 0;
  std::size_t data = 0, data_size = 0;  // offset and size of its data
};

class Walker {
 public:
  Walker(const ByteSource& bytes, const std::string& where) : b_(bytes), where_(where) {}

  [[noreturn]] void fail(std::size_t offset, const std::string& problem) const {
    throw Error(where_, "damaged ROS bag at byte " + std::to_string(offset) + ": " + problem);
  }

  // Calls visit(record) for each record of [begin, end), in order, keeping none.
  template <class Visit>
  void each_record(std::size_t begin, std::size_t end, const char* inside, Visit&& visit) const {
    std::size_t p = begin;
    while (p < end) {
      Record r;
      r.offset = p;
      const std::size_t header_size = length_at(p, end, "record header", inside);
      const std::size_t h = p + 4;
      r.fields = fields(h, header_size, "its record header");
      const auto op = r.fields.find("op");
      if (op == r.fields.end() || op->second.size() != 1) fail(p, "record without a one-byte op field");
      r.op = static_cast<unsigned char>(op->second[0]);
      const std::size_t d = h + header_size;
      r.data_size = length_at(d, end, "record data", inside);
      r.data = d + 4;
      // A connection record's data is a header too (the topic's connection header: type,
      // md5sum, message_definition), parsed by roscpp's ros::Header, which checks a field's
      // length against 1 MB but not against the bytes left (a read past the buffer, fuzz_bag).
      if (r.op == kConnection) fields(r.data, r.data_size, "its connection header");
      p = r.data + r.data_size;
      visit(r);
    }
  }

  // The name=value fields, each with a 4-byte length, filling [h, h + size) exactly.
  std::map<std::string, std::string> fields(std::size_t h, std::size_t size, const char* inside) const {
    if (size > kMaxHeaderSize) fail(h, std::string("a header of ") + std::to_string(size) + " bytes in " + inside);
    const std::string bytes = b_.read(h, size);
    std::map<std::string, std::string> out;
    std::size_t q = 0;
    while (q < size) {
      if (size - q < 4) fail(h + q, std::string("truncated header field length in ") + inside);
      const std::uint64_t field_size = read_le(bytes.data() + q, 4);
      if (field_size > size - q - 4)
        fail(h + q, "header field of " + std::to_string(field_size) + " bytes runs past the end of " + inside);
      const std::string field = bytes.substr(q + 4, std::size_t(field_size));
      const std::size_t eq = field.find('=');
      if (eq == std::string::npos) fail(h + q, "header field without '='");
      out[field.substr(0, eq)] = field.substr(eq + 1);
      q += 4 + std::size_t(field_size);
    }
    return out;
  }

  std::uint64_t integer(const Record& r, const char* name, std::size_t size) const {
    const auto f = r.fields.find(name);
    if (f == r.fields.end()) fail(r.offset, std::string("record without its '") + name + "' field");
    if (f->second.size() != size)
      fail(r.offset, std::string("field '") + name + "' holds " + std::to_string(f->second.size()) + " bytes, not " +
                         std::to_string(size));
    return read_le(f->second.data(), size);
  }

  std::uint64_t le_at(std::size_t p, std::size_t n) const { return read_le(b_.read(p, n).data(), n); }

 private:
  // A 4-byte length at p followed by that many bytes, all before `end`.
  std::size_t length_at(std::size_t p, std::size_t end, const char* what, const char* inside) const {
    if (end - p < 4) fail(p, std::string("truncated ") + what + " length");
    const std::uint64_t n = le_at(p, 4);
    if (n > end - p - 4)
      fail(p, std::string(what) + " of " + std::to_string(n) + " bytes runs past the end of " + inside);
    return std::size_t(n);
  }

  const ByteSource& b_;
  const std::string& where_;
};

// What the walk over the top-level records keeps: an op per record offset (what index_pos and the
// chunk infos must point at), the record starts of the last uncompressed chunk (what its index
// records, which follow it, must point at), and the index section's counts.
struct TopLevel {
  std::map<std::size_t, unsigned char> op_at;
  std::optional<std::set<std::size_t>> last_chunk_starts;  // nullopt: the last chunk is compressed
  bool any_chunk = false;
  std::vector<std::pair<std::size_t, unsigned char>> after_index;  // records from index_pos on
};

void check_chunk(const Walker& w, const Record& r, TopLevel& t) {
  t.any_chunk = true;
  t.last_chunk_starts.reset();
  const auto c = r.fields.find("compression");
  if (c == r.fields.end()) w.fail(r.offset, "chunk without its 'compression' field");
  const std::uint64_t size = w.integer(r, "size", 4);
  if (c->second == "none") {
    if (size != r.data_size)
      w.fail(r.offset,
             "uncompressed chunk declares " + std::to_string(size) + " bytes but holds " + std::to_string(r.data_size));
    std::set<std::size_t> starts;
    w.each_record(r.data, r.data + r.data_size, "its chunk", [&](const Record& inner) {
      if (inner.op != kMessage && inner.op != kConnection)
        w.fail(inner.offset, "a chunk holds a record that is neither a message nor a connection");
      starts.insert(inner.offset - r.data);
    });
    t.last_chunk_starts = std::move(starts);
  } else if (c->second == "bz2" || c->second == "lz4") {
    if (size > kMaxChunkSize)
      w.fail(r.offset, "chunk declares " + std::to_string(size) + " bytes uncompressed, more than 1 GiB");
  } else {
    w.fail(r.offset, "unknown chunk compression '" + c->second + "'");
  }
}

void check_index(const Walker& w, const Record& r, const TopLevel& t) {
  if (w.integer(r, "ver", 4) != 1) w.fail(r.offset, "index record of a version other than 1");
  const std::uint64_t count = w.integer(r, "count", 4);
  w.integer(r, "conn", 4);
  if (count * 12 != r.data_size)
    w.fail(r.offset,
           "index record of " + std::to_string(count) + " entries holds " + std::to_string(r.data_size) + " bytes");
  if (!t.any_chunk) w.fail(r.offset, "index record before any chunk");
  if (!t.last_chunk_starts) return;  // a compressed chunk: rosbag checks
  for (std::uint64_t e = 0; e < count; ++e) {
    const std::uint64_t off = w.le_at(r.data + std::size_t(e) * 12 + 8, 4);
    if (!t.last_chunk_starts->count(std::size_t(off)))
      w.fail(r.offset, "index entry points at offset " + std::to_string(off) + " of its chunk, where no record starts");
  }
}

void check_chunk_info(const Walker& w, const Record& r) {
  if (w.integer(r, "ver", 4) != 1) w.fail(r.offset, "chunk info record of a version other than 1");
  w.integer(r, "chunk_pos", 8);
  w.integer(r, "start_time", 8);
  w.integer(r, "end_time", 8);
  const std::uint64_t count = w.integer(r, "count", 4);
  if (count * 8 != r.data_size)
    w.fail(r.offset,
           "chunk info of " + std::to_string(count) + " connections holds " + std::to_string(r.data_size) + " bytes");
}

}  // namespace

// Long on purpose: the bag records walked in file order, each length checked before it is trusted.
static void check_bag_source(const ByteSource& bytes, const std::string& where) {
  if (bytes.size() < kMagicSize || bytes.read(0, kMagicSize) != kMagic)
    throw Error(where, "not a readable ROS bag: it does not start with '#ROSBAG V2.0' (bag format 2.0)");
  const Walker w(bytes, where);
  TopLevel t;
  std::optional<Record> header;
  std::uint64_t index_pos = 0;
  std::vector<std::pair<std::size_t, std::uint64_t>> chunk_infos;  // record offset, chunk_pos
  w.each_record(kMagicSize, bytes.size(), "the file", [&](const Record& r) {
    if (!header) {
      if (r.op != kBagHeader) w.fail(kMagicSize, "the first record is not the bag header");
      header = r;
      index_pos = w.integer(r, "index_pos", 8);
    }
    t.op_at[r.offset] = r.op;
    if (r.offset >= index_pos && index_pos > 0) t.after_index.emplace_back(r.offset, r.op);
    if (r.op == kChunk) {
      check_chunk(w, r, t);
    } else if (r.op == kIndex) {
      check_index(w, r, t);
    } else if (r.op == kChunkInfo) {
      check_chunk_info(w, r);
      chunk_infos.emplace_back(r.offset, w.integer(r, "chunk_pos", 8));
    } else if (r.op == kConnection) {
      w.integer(r, "conn", 4);
      if (!r.fields.count("topic")) w.fail(r.offset, "connection record without its 'topic' field");
    }
  });
  if (!header) w.fail(kMagicSize, "the first record is not the bag header");
  for (const auto& [offset, pos] : chunk_infos) {
    const auto c = t.op_at.find(std::size_t(pos));
    if (pos > bytes.size() || c == t.op_at.end() || c->second != kChunk)
      w.fail(offset, "chunk info points at byte " + std::to_string(pos) + ", where no chunk starts");
  }

  // The index section rosbag seeks to: conn_count connections, then chunk_count chunk infos.
  const std::uint64_t conn_count = w.integer(*header, "conn_count", 4);
  const std::uint64_t chunk_count = w.integer(*header, "chunk_count", 4);
  if (index_pos > bytes.size() || !t.op_at.count(std::size_t(index_pos)))
    w.fail(header->offset,
           "index_pos " + std::to_string(index_pos) +
               " is not the start of a record (an unindexed or damaged bag: `rosbag reindex` may repair it)");
  std::uint64_t connections = 0, infos = 0;
  for (const auto& [offset, op] : t.after_index) {
    if (op == kConnection && infos == 0)
      ++connections;
    else if (op == kChunkInfo)
      ++infos;
    else
      w.fail(offset, "the index section holds a record that is neither a connection nor a chunk info");
  }
  if (connections != conn_count || infos != chunk_count)
    w.fail(header->offset, "the bag header counts " + std::to_string(conn_count) + " connections and " +
                               std::to_string(chunk_count) + " chunks; its index holds " + std::to_string(connections) +
                               " and " + std::to_string(infos));
}

void check_bag(const std::string& bytes, const std::string& where) { check_bag_source(StringSource(bytes), where); }

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

void check_bag_file(const std::string& path) { check_bag_source(FileSource(path), path); }

}  // namespace cropsight::ros_io::detail
