// PCD/PLY through PCL: every channel round-trips, organised layout survives, PCL's own typed
// readers agree with ours, failed writes leave nothing.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <tuple>

#include "cropsight/core/error.hpp"
#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/files.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

using testing::TempDir;
namespace fs = std::filesystem;

OrganizedCloud make_organized(bool color, bool labels, bool normals) {
  OrganizedCloud c(7, 5);
  for (int v = 0; v < 5; ++v)
    for (int u = 0; u < 7; ++u) {
      const int i = c.index(u, v);
      if ((u + 2 * v) % 5 == 0) continue;  // NaN hole
      c.x[std::size_t(i)] = 0.01f * u - 0.03f;
      c.y[std::size_t(i)] = 0.013f * v;
      c.z[std::size_t(i)] = 1.25f + 0.001f * float(i);
    }
  if (color) {
    c.color.resize(c.size());
    for (std::size_t i = 0; i < c.size(); ++i)
      c.color[i] = {std::uint8_t(i * 7), std::uint8_t(255 - i), std::uint8_t(i * 3)};
  }
  if (labels) {
    c.labels.resize(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) c.labels[i] = std::uint16_t(i % 4 == 0 ? 0 : 1000 + i);
  }
  if (normals) {
    c.allocate_normals();
    for (std::size_t i = 0; i < c.size(); i += 2) {
      c.nx[i] = 0.0f;
      c.ny[i] = 0.6f;
      c.nz[i] = -0.8f;
      c.curvature[i] = 0.01f * float(i);
    }
  }
  return c;
}

bool same_float(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

void expect_same(const OrganizedCloud& a, const OrganizedCloud& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(same_float(a.x[i], b.x[i]) && same_float(a.y[i], b.y[i]) && same_float(a.z[i], b.z[i])) << i;
  }
  EXPECT_EQ(a.color, b.color);
  EXPECT_EQ(a.labels, b.labels);
  ASSERT_EQ(a.has_normals(), b.has_normals());
  for (std::size_t i = 0; i < a.nx.size(); ++i)
    EXPECT_TRUE(same_float(a.nx[i], b.nx[i]) && same_float(a.ny[i], b.ny[i]) && same_float(a.nz[i], b.nz[i]) &&
                same_float(a.curvature[i], b.curvature[i]))
        << i;
}

class OrganizedRoundTrip : public ::testing::TestWithParam<std::tuple<std::string, bool>> {};

TEST_P(OrganizedRoundTrip, EveryChannel) {
  const auto [ext, binary] = GetParam();
  TempDir tmp;
  for (int mask = 0; mask < 8; ++mask) {
    const OrganizedCloud c = make_organized(mask & 1, mask & 2, mask & 4);
    const fs::path p = tmp / ("c" + std::to_string(mask) + ext);
    write_cloud(p, c, binary);
    SCOPED_TRACE(p.string());
    expect_same(read_organized_cloud(p), c);
    EXPECT_EQ(read_cloud(p).size(), c.count_valid());
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, OrganizedRoundTrip,
                         ::testing::Values(std::make_tuple(".pcd", true), std::make_tuple(".pcd", false),
                                           std::make_tuple(".ply", true), std::make_tuple(".ply", false)));

TEST(CloudIo, PclTypedReaderAgreesOnOrganisedColourPcd) {
  TempDir tmp;
  const OrganizedCloud c = make_organized(true, false, false);
  write_cloud(tmp / "c.pcd", c);
  pcl::PointCloud<pcl::PointXYZRGB> pc;
  ASSERT_EQ(pcl::io::loadPCDFile(tmp / "c.pcd", pc), 0);
  EXPECT_EQ(pc.width, 7u);
  EXPECT_EQ(pc.height, 5u);
  EXPECT_FALSE(pc.is_dense);
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_TRUE(same_float(pc[i].z, c.z[i]));
    EXPECT_EQ(pc[i].r, c.color[i].r);
    EXPECT_EQ(pc[i].g, c.color[i].g);
    EXPECT_EQ(pc[i].b, c.color[i].b);
  }
}

TEST(CloudIo, PclTypedReaderAgreesOnPly) {
  TempDir tmp;
  const OrganizedCloud c = make_organized(true, false, false);
  write_cloud(tmp / "c.ply", c);
  pcl::PointCloud<pcl::PointXYZRGB> pc;
  ASSERT_EQ(pcl::io::loadPLYFile(tmp / "c.ply", pc), 0);
  EXPECT_EQ(pc.width, 7u);
  EXPECT_EQ(pc.height, 5u);
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_TRUE(same_float(pc[i].x, c.x[i]));
    EXPECT_EQ(pc[i].r, c.color[i].r);
  }
}

// PCL's own compressed PCD passes the header checks; the same file with another uncompressed
// size (PCL would resize the points to it and write past them) does not.
TEST(CloudIo, PclBinaryCompressedPcdReads) {
  TempDir tmp;
  pcl::PointCloud<pcl::PointXYZ> pc;
  for (int i = 0; i < 30; ++i) pc.push_back(pcl::PointXYZ(0.1f * float(i), -0.2f, 1.0f + 0.01f * float(i)));
  ASSERT_EQ(pcl::PCDWriter().writeBinaryCompressed((tmp / "c.pcd").string(), pc), 0);
  const Cloud r = read_cloud(tmp / "c.pcd");
  ASSERT_EQ(r.points.size(), 30u);
  EXPECT_TRUE(same_float(r.points[29].x(), pc[29].x));
  std::string bytes = read_file(tmp / "c.pcd");
  const std::size_t body = bytes.find("DATA binary_compressed\n") + 23;
  bytes[body + 4] = char(bytes[body + 4] - 12);  // uncompressed size: one point less
  write_file_atomic(tmp / "short.pcd", bytes);
  try {
    read_cloud(tmp / "short.pcd");
    ADD_FAILURE() << "no error for a compressed PCD of the wrong uncompressed size";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bytes uncompressed; its header's points take 360"), std::string::npos)
        << e.what();
  }
}

TEST(CloudIo, UnorganisedRoundTrip) {
  TempDir tmp;
  Cloud c;
  for (int i = 0; i < 20; ++i) {
    c.points.emplace_back(0.1f * i, -0.2f * i, 1.0f + 0.01f * i);
    c.normals.emplace_back(Eigen::Vector3f(1, i, 2).normalized());
    c.colors.emplace_back(i / 19.0f, 1.0f - i / 19.0f, 0.5f);
    c.labels.push_back(i % 3 - 1);  // includes -1 (noise)
  }
  for (const char* name : {"u.pcd", "u.ply"}) {
    write_cloud(tmp / name, c);
    const Cloud r = read_cloud(tmp / name);
    ASSERT_EQ(r.size(), c.size()) << name;
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_EQ(r.points[i], c.points[i]);
      EXPECT_EQ(r.normals[i], c.normals[i]);
      EXPECT_NEAR(r.colors[i].x(), c.colors[i].x(), 0.5f / 255.0f + 1e-6f);
      EXPECT_EQ(r.labels[i], c.labels[i]);
    }
    EXPECT_THROW(read_organized_cloud(tmp / name), Error);  // height 1
  }
}

TEST(CloudIo, ErrorsNameTheFile) {
  TempDir tmp;
  const OrganizedCloud c = make_organized(false, false, false);
  try {
    write_cloud(tmp / "c.xyz", c);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), (tmp / "c.xyz").string());
  }
  try {
    read_cloud(tmp / "missing.pcd");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), (tmp / "missing.pcd").string());
  }
  // Garbage and truncated files: an Error naming the file, never a crash inside PCL.
  const std::string header =
      "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 2\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 8\nDATA ascii\n";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"garbage.pcd", "this is not a pcd file\n"},
      {"empty.pcd", ""},
      {"truncated.pcd", header + "1 2 3\n4 5 6\n"},
      {"garbage.ply", "this is not a ply file\n"},
      {"truncated.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 10\nproperty float x\n"
       "property float y\nproperty float z\nend_header\n1234"},
  };
  for (const auto& [name, text] : bad) {
    write_file_atomic(tmp / name, text);
    try {
      read_cloud(tmp / name);
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), (tmp / name).string());
    }
  }
}

// What fuzz_pcd and fuzz_ply found (fuzz/regressions/): a label that is NaN was converted to int
// (undefined behaviour), and PCL's PLY reader asserted (abort) on a property line with extra
// tokens; io::detail::check_ply now refuses malformed headers and short bodies first.
TEST(CloudIo, FuzzFindingsAreErrors) {
  TempDir tmp;
  const std::string ply_head = "ply\nformat ascii 1.0\nelement vertex 2\n";
  const std::vector<std::tuple<std::string, std::string, std::string>> bad = {
      {"nan_label.pcd",
       "VERSION .7\nFIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 1\nHEIGHT 1\n"
       "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n0.1 0.2 0.3 nan\n",
       "label of point 0 is not an integer"},
      {"extra_tokens.ply",
       ply_head + "property float x\nproperty float y\nproperty float z\nproperty uchar red+property uchar green\n"
                  "end_header\n0 0 1 5\n0 1 1 6\n",
       "line 7: expected 'property TYPE NAME'"},
      {"unknown_type.ply", ply_head + "property float x\nproperty flot y\nend_header\n", "line 5"},
      {"too_few_lines.ply", ply_head + "property float x\nproperty float y\nproperty float z\nend_header\n0 0 1\n",
       "PLY data ends early"},
      {"values_per_line.ply",
       ply_head + "property float x\nproperty float y\nproperty float z\nend_header\n0 0 1\n0 1\n",
       "2 values where element 'vertex' has 3"},
      {"huge_count.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\n"
       "property float z\nend_header\n0123456789ab",
       "PLY data ends early"},
      {"no_end.ply", ply_head + "property float x\n", "no 'end_header'"},
      // A 30-minute run: a CR inside an obj_info line made PCL's callback assert.
      {"cr_in_obj_info.ply", "ply\nobj_info\r<\rply\n" + ply_head.substr(4) + "property float x\nend_header\n",
       "line 2: a control character in a header line"},
      // Second sweep: green and blue without red wrote past PCL's point (assert).
      {"green_without_red.ply",
       ply_head + "property float x\nproperty float y\nproperty float z\nproperty uchar green\nproperty uchar blue\n"
                  "end_header\n0 0 1 5 6\n0 1 1 6 7\n",
       "vertex colour must be uchar red, green, blue"},
      // Third sweep: PCL reads header lines by prefix and goes on after DATA, so body bytes that
      // read as "COLUMNS ..." redefined the fields after the checks (a read 2 GB past the data).
      {"columns_after_data.pcd",
       "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
       "DATA binary\nCOLUMNS a b c d\nSIZE 4 4 4 4\n",
       "line 10: a line after DATA that PCL reads as header ('FIELDS')"},
      {"prefix_keyword.pcd",
       "VERSION .7\nFIELDS x y z\nFIELDSX a\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n0 0 1\n",
       "line 3: FIELDS given twice"},
      {"unknown_keyword.pcd",
       "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nLENGTH 3\nWIDTH 1\nPOINTS 1\nDATA ascii\n0 0 1\n",
       "line 5: 'LENGTH' is not a PCD header keyword"},
      // PCL sized the points at POINTS (12 bytes each here), then wrote 24-byte points.
      {"points_before_size.pcd",
       "VERSION .7\nFIELDS x y z\nPOINTS 2\nSIZE 8 8 8\nTYPE F F F\nWIDTH 2\nDATA ascii\n1 2 3\n4 5 6\n",
       "line 4: SIZE after POINTS"},
      {"float_of_two_bytes.pcd",
       "VERSION .7\nFIELDS x y z\nSIZE 4 4 2\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n0 0 1\n",
       "line 4: TYPE F of field 3 needs SIZE 4 or 8, not 2"},
      {"no_type.pcd", "VERSION .7\nFIELDS x y z\nSIZE 4 4 2\nWIDTH 1\nPOINTS 1\nDATA ascii\n0 0 1\n",
       "malformed PCD header (needs"},
      {"blank_line_ends_header.pcd",
       "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n  \nWIDTH 1\nPOINTS 1\nDATA ascii\n0 0 1\n", "no DATA line"},
  };
  for (const auto& [name, text, words] : bad) {
    write_file_atomic(tmp / name, text);
    try {
      read_cloud(tmp / name);
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), (tmp / name).string());
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << name << ": " << e.what();
    }
  }
  // The second sweep's PCD: a second SIZE line gave fields sizes that do not fit the point, and
  // reading them went past the data (SEGV). Read straight from fuzz/regressions/.
  // The third sweep's: header lines after DATA (a read past the data, and in an earlier input a
  // write that broke ASan's heap).
  for (const char* name : {"crash-7f9a3e374ca9", "crash-204537d87fe2", "crash-6a1579ca9f15"}) {
    const std::string pcd = std::string(CROPSIGHT_SOURCE_DIR) + "/fuzz/regressions/pcd/" + name;
    const fs::path copy = tmp / (std::string(name) + ".pcd");  // the reader picks the format by extension
    try {
      fs::copy_file(pcd, copy);
      read_cloud(copy);
      ADD_FAILURE() << "no error for " << pcd;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), copy.string()) << e.what();
    }
  }
  // A well-formed ascii PLY with a list element (faces) still reads.
  write_file_atomic(tmp / "faces.ply", ply_head +
                                           "property float x\nproperty float y\nproperty float z\n"
                                           "element face 1\nproperty list uchar int vertex_indices\n"
                                           "end_header\n0 0 1\n0 1 1\n2 0 1\n");
  EXPECT_EQ(read_cloud(tmp / "faces.ply").size(), 2u);
}

TEST(CloudIo, FailedWriteLeavesNothing) {
  TempDir tmp;
  OrganizedCloud broken(4, 4);
  broken.x.pop_back();  // inconsistent
  EXPECT_THROW(write_cloud(tmp / "b.pcd", broken), Error);
  EXPECT_THROW(write_cloud(tmp / "b.txt", make_organized(false, false, false)), Error);
  EXPECT_TRUE(fs::is_empty(tmp.path()));
}

}  // namespace
}  // namespace cropsight::io
