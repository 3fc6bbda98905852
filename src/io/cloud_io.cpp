// PCD and PLY files through PCL's readers and writers. Clouds are converted to and from a
// pcl::PCLPointCloud2 blob whose fields are built here (x y z, optional normal_x/y/z and
// curvature, rgb packed PCL-style, label), so every channel of our clouds survives a round trip
// and organised clouds keep width×height (PCD: WIDTH/HEIGHT; PLY: PCL's camera element).
#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/file_names.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <cmath>

#include <cstring>
#include <limits>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "pcd_check.hpp"
#include "ply_check.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

using pcl::PCLPointField;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

enum class Format { kPcd, kPly };

Format format_of(const fs::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".pcd") return Format::kPcd;
  if (ext == ".ply") return Format::kPly;
  throw Error(path.string(), "unknown point-cloud format '" + ext + "' (expected .pcd or .ply)");
}

/// Builds the field list of a blob; offsets are assigned in order, 4 bytes per field.
struct BlobBuilder {
  pcl::PCLPointCloud2 blob;
  std::uint32_t offset = 0;
  void add(const std::string& name, std::uint8_t type) {
    PCLPointField f;
    f.name = name;
    f.offset = offset;
    f.datatype = type;
    f.count = 1;
    blob.fields.push_back(f);
    offset += 4;
  }
  void allocate(std::uint32_t width, std::uint32_t height) {
    blob.width = width;
    blob.height = height;
    blob.point_step = offset;
    blob.row_step = offset * width;
    blob.is_bigendian = false;
    blob.data.assign(std::size_t(offset) * width * height, 0);
  }
  template <typename T>
  void set(std::size_t point, int field, T value) {
    static_assert(sizeof(T) == 4);
    std::memcpy(&blob.data[point * blob.point_step + blob.fields[std::size_t(field)].offset], &value, 4);
  }
};

std::uint32_t pack_rgb(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  // PCL packs colour as 0xAARRGGBB in a float-typed "rgb" field (little endian: b, g, r, a).
  return (std::uint32_t(255) << 24) | (std::uint32_t(r) << 16) | (std::uint32_t(g) << 8) | std::uint32_t(b);
}
float as_float(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

void save(const fs::path& path, const pcl::PCLPointCloud2& blob, bool binary) {
  const Format format = format_of(path);
  write_atomic_with(path, [&](const fs::path& tmp) {
    int rc = 0;
    if (format == Format::kPcd) {
      pcl::PCDWriter w;
      rc = binary ? w.writeBinary(tmp.string(), blob)
                  : w.writeASCII(tmp.string(), blob, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), 8);
    } else {
      pcl::PLYWriter w;
      // use_camera=true stores width/height in PCL's camera element, so organised layout survives.
      rc = w.write(tmp.string(), blob, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), binary, true);
    }
    if (rc != 0) throw Error(path.string(), "PCL could not write the point cloud");
  });
}

/// PCL prints its own warnings and errors on stderr; ours (one Error line) replace them, so PCL
/// is silenced while it reads. (PCL's verbosity is a process-wide setting; it is restored.)
class QuietPcl {
 public:
  QuietPcl() : level_(pcl::console::getVerbosityLevel()) { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); }
  ~QuietPcl() { pcl::console::setVerbosityLevel(level_); }

 private:
  pcl::console::VERBOSITY_LEVEL level_;
};

pcl::PCLPointCloud2 load(const fs::path& path) {
  const Format format = format_of(path);
  if (!fs::exists(path)) throw Error(path.string(), "file not found");
  QuietPcl quiet;
  pcl::PCLPointCloud2 blob;
  int rc = -1;
  try {
    if (format == Format::kPcd) {
      // PCL 1.13's PCDReader::read crashes on some malformed headers (no fields, no points), so
      // the header is read and checked on its own first.
      // PCL sizes its buffer from the header before reading any data (fuzz_pcd: 21 GB).
      detail::check_pcd_header(read_file(path), path.string());
      pcl::PCDReader reader;
      Eigen::Vector4f origin;
      Eigen::Quaternionf orientation;
      int version = 0, data_type = 0;
      unsigned int data_idx = 0;
      if (reader.readHeader(path.string(), blob, origin, orientation, version, data_type, data_idx) < 0 ||
          blob.fields.empty() || blob.width == 0 || blob.height == 0 || blob.point_step == 0)
        throw Error(path.string(),
                    "malformed PCD header (needs FIELDS, SIZE, TYPE, COUNT, WIDTH, HEIGHT, POINTS, DATA)");
      blob = pcl::PCLPointCloud2();
      rc = reader.read(path.string(), blob);
    } else {
      detail::check_ply(read_file(path), path.string());  // PCL's PLY reader asserts on malformed files
      rc = pcl::io::loadPLYFile(path.string(), blob);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path.string(), std::string("cannot read point cloud: ") + e.what());
  }
  if (rc < 0) throw Error(path.string(), "cannot read point cloud (malformed or unsupported file)");
  const unsigned __int128 need = (unsigned __int128)blob.width * blob.height * blob.point_step;  // no overflow
  if (need > blob.data.size()) throw Error(path.string(), "point data is shorter than its header says");
  // Every field must lie inside its point (fuzz_pcd: an offset past point_step read past the data).
  for (const auto& f : blob.fields) {
    const std::size_t size = pcl::getFieldSize(f.datatype);
    if (size == 0) throw Error(path.string(), "field '" + f.name + "' has an unknown type");
    if (std::uint64_t(f.offset) + std::uint64_t(size) * std::max<std::uint32_t>(f.count, 1) > blob.point_step)
      throw Error(path.string(),
                  "field '" + f.name + "' does not fit in a point of " + std::to_string(blob.point_step) + " bytes");
  }
  return blob;
}

/// Reads field `name` of every point as float (numeric types converted); empty when absent.
class FieldReader {
 public:
  explicit FieldReader(const pcl::PCLPointCloud2& blob) : blob_(blob) {}
  const PCLPointField* find(const std::string& name) const {
    for (const auto& f : blob_.fields)
      if (f.name == name) return &f;
    return nullptr;
  }
  double value(std::size_t i, const PCLPointField& f) const {
    const std::uint8_t* p = &blob_.data[i * blob_.point_step + f.offset];
    switch (f.datatype) {
      case PCLPointField::INT8:
        return double(*reinterpret_cast<const std::int8_t*>(p));
      case PCLPointField::UINT8:
        return double(*p);
      case PCLPointField::INT16: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return v;
      }
      case PCLPointField::UINT16: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
      }
      case PCLPointField::INT32: {
        std::int32_t v;
        std::memcpy(&v, p, 4);
        return v;
      }
      case PCLPointField::UINT32: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
      }
      case PCLPointField::FLOAT32: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
      }
      case PCLPointField::FLOAT64: {
        double v;
        std::memcpy(&v, p, 8);
        return v;
      }
      default:
        return std::numeric_limits<double>::quiet_NaN();
    }
  }
  std::uint32_t bits32(std::size_t i, const PCLPointField& f) const {
    std::uint32_t v;
    std::memcpy(&v, &blob_.data[i * blob_.point_step + f.offset], 4);
    return v;
  }

 private:
  const pcl::PCLPointCloud2& blob_;
};

const PCLPointField* color_field(const FieldReader& r, const fs::path& path) {
  const PCLPointField* f = r.find("rgb");
  if (!f) f = r.find("rgba");
  if (f && pcl::getFieldSize(f->datatype) != 4) throw Error(path.string(), "colour field is not 4 bytes wide");
  return f;
}

// The PCD/PLY fields of a written cloud, in PCL's names and order: x y z [normal_x normal_y
// normal_z [curvature]] [rgb] [label]. Returns the field index of normal_x, rgb and label (-1: absent).
struct CloudFieldIndex {
  int normals = -1, rgb = -1, label = -1;
};
CloudFieldIndex add_cloud_fields(BlobBuilder& b, bool normals, bool curvature, bool rgb, bool label,
                                 std::uint8_t label_type) {
  CloudFieldIndex at;
  b.add("x", PCLPointField::FLOAT32);
  b.add("y", PCLPointField::FLOAT32);
  b.add("z", PCLPointField::FLOAT32);
  if (normals) {
    at.normals = int(b.blob.fields.size());
    b.add("normal_x", PCLPointField::FLOAT32);
    b.add("normal_y", PCLPointField::FLOAT32);
    b.add("normal_z", PCLPointField::FLOAT32);
    if (curvature) b.add("curvature", PCLPointField::FLOAT32);
  }
  if (rgb) {
    at.rgb = int(b.blob.fields.size());
    b.add("rgb", PCLPointField::FLOAT32);
  }
  if (label) {
    at.label = int(b.blob.fields.size());
    b.add("label", label_type);
  }
  return at;
}

}  // namespace

void write_cloud(const fs::path& path, const OrganizedCloud& cloud, bool binary) {
  if (cloud.width <= 0 || cloud.height <= 0 || cloud.size() != std::size_t(cloud.width) * std::size_t(cloud.height))
    throw Error(path.string(), "cannot write an empty or inconsistent organised cloud");
  BlobBuilder b;
  const auto [fn, frgb, flabel] =
      add_cloud_fields(b, cloud.has_normals(), true, cloud.has_color(), cloud.has_labels(), PCLPointField::UINT32);
  b.allocate(std::uint32_t(cloud.width), std::uint32_t(cloud.height));
  bool dense = true;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    b.set(i, 0, cloud.x[i]);
    b.set(i, 1, cloud.y[i]);
    b.set(i, 2, cloud.z[i]);
    dense = dense && cloud.valid(i);
    if (fn >= 0) {
      b.set(i, fn, cloud.nx[i]);
      b.set(i, fn + 1, cloud.ny[i]);
      b.set(i, fn + 2, cloud.nz[i]);
      b.set(i, fn + 3, cloud.curvature.empty() ? kNaN : cloud.curvature[i]);
    }
    if (frgb >= 0) b.set(i, frgb, as_float(pack_rgb(cloud.color[i].r, cloud.color[i].g, cloud.color[i].b)));
    if (flabel >= 0) b.set(i, flabel, std::uint32_t(cloud.labels[i]));
  }
  b.blob.is_dense = dense;
  save(path, b.blob, binary);
}

void write_cloud(const fs::path& path, const Cloud& cloud, bool binary) {
  cloud.validate(path.string());
  BlobBuilder b;
  const auto [fn, frgb, flabel] =
      add_cloud_fields(b, cloud.has_normals(), false, cloud.has_colors(), cloud.has_labels(), PCLPointField::INT32);
  b.allocate(std::uint32_t(cloud.size()), 1);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int k = 0; k < 3; ++k) b.set(i, k, cloud.points[i][k]);
    if (fn >= 0)
      for (int k = 0; k < 3; ++k) b.set(i, fn + k, cloud.normals[i][k]);
    if (frgb >= 0) {
      const Eigen::Vector3f c = (cloud.colors[i] * 255.0f).cwiseMax(0.0f).cwiseMin(255.0f);
      b.set(i, frgb,
            as_float(pack_rgb(std::uint8_t(c.x() + 0.5f), std::uint8_t(c.y() + 0.5f), std::uint8_t(c.z() + 0.5f))));
    }
    if (flabel >= 0) b.set(i, flabel, std::int32_t(cloud.labels[i]));
  }
  b.blob.is_dense = true;
  save(path, b.blob, binary);
}

OrganizedCloud read_organized_cloud(const fs::path& path) {
  const pcl::PCLPointCloud2 blob = load(path);
  if (blob.height <= 1)
    throw Error(path.string(), "not an organised cloud (height " + std::to_string(blob.height) + "; expected > 1)");
  const FieldReader r(blob);
  const PCLPointField *fx = r.find("x"), *fy = r.find("y"), *fz = r.find("z");
  if (!fx || !fy || !fz) throw Error(path.string(), "missing x, y or z field");
  OrganizedCloud out(int(blob.width), int(blob.height));
  const PCLPointField *nx = r.find("normal_x"), *ny = r.find("normal_y"), *nz = r.find("normal_z");
  const PCLPointField* curv = r.find("curvature");
  const PCLPointField* rgb = color_field(r, path);
  const PCLPointField* label = r.find("label");
  const bool normals = nx && ny && nz;
  if (normals) out.allocate_normals();
  if (rgb) out.color.resize(out.size());
  if (label) out.labels.resize(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const float x = float(r.value(i, *fx)), y = float(r.value(i, *fy)), z = float(r.value(i, *fz));
    if (std::isfinite(x) && std::isfinite(y) && std::isfinite(z)) {
      out.x[i] = x;
      out.y[i] = y;
      out.z[i] = z;
    }
    if (normals) {
      out.nx[i] = float(r.value(i, *nx));
      out.ny[i] = float(r.value(i, *ny));
      out.nz[i] = float(r.value(i, *nz));
      if (curv) out.curvature[i] = float(r.value(i, *curv));
    }
    if (rgb) {
      const std::uint32_t c = r.bits32(i, *rgb);
      out.color[i] = {std::uint8_t((c >> 16) & 0xff), std::uint8_t((c >> 8) & 0xff), std::uint8_t(c & 0xff)};
    }
    if (label) {
      const double l = r.value(i, *label);
      out.labels[i] = (l >= 0 && l <= 65535) ? std::uint16_t(l) : std::uint16_t(0);
    }
  }
  return out;
}

Cloud read_cloud(const fs::path& path) {
  const pcl::PCLPointCloud2 blob = load(path);
  const FieldReader r(blob);
  const PCLPointField *fx = r.find("x"), *fy = r.find("y"), *fz = r.find("z");
  if (!fx || !fy || !fz) throw Error(path.string(), "missing x, y or z field");
  const PCLPointField *nx = r.find("normal_x"), *ny = r.find("normal_y"), *nz = r.find("normal_z");
  const PCLPointField* rgb = color_field(r, path);
  const PCLPointField* label = r.find("label");
  const bool normals = nx && ny && nz;
  Cloud out;
  const std::size_t n = std::size_t(blob.width) * blob.height;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f p(float(r.value(i, *fx)), float(r.value(i, *fy)), float(r.value(i, *fz)));
    if (!p.allFinite()) continue;  // organised files have NaN holes
    out.points.push_back(p);
    if (normals) out.normals.emplace_back(float(r.value(i, *nx)), float(r.value(i, *ny)), float(r.value(i, *nz)));
    if (rgb) {
      const std::uint32_t c = r.bits32(i, *rgb);
      out.colors.emplace_back(float((c >> 16) & 0xff) / 255.0f, float((c >> 8) & 0xff) / 255.0f,
                              float(c & 0xff) / 255.0f);
    }
    if (label) {
      // A float label field may hold NaN or 1e30 (fuzz_pcd found it): converting those to int is
      // undefined behaviour, so anything but an integer in int's range is an error.
      const double l = r.value(i, *label);
      if (!(l >= double(std::numeric_limits<int>::min()) && l <= double(std::numeric_limits<int>::max())) ||
          l != std::floor(l))
        throw Error(path.string(), "label of point " + std::to_string(i) + " is not an integer");
      out.labels.push_back(int(l));
    }
  }
  return out;
}

}  // namespace cropsight::io
