// geo_origin.yaml and the field <-> WGS84 conversion through PROJ.
#include "cropsight/io/geo_origin.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace geo_origin_test {

namespace fs = std::filesystem;

// Metres per degree of latitude near 52° N on WGS84 (meridian arc), for the independent checks below.
double metres_per_degree_latitude(double lat_deg) {
  const double a = 6378137.0, e2 = 0.00669437999014, phi = lat_deg * M_PI / 180.0;
  const double s = std::sin(phi);
  return M_PI / 180.0 * a * (1 - e2) / std::pow(1 - e2 * s * s, 1.5);
}
double metres_per_degree_longitude(double lat_deg) {
  const double a = 6378137.0, e2 = 0.00669437999014, phi = lat_deg * M_PI / 180.0;
  const double s = std::sin(phi);
  return M_PI / 180.0 * a * std::cos(phi) / std::sqrt(1 - e2 * s * s);
}

TEST(GeoOrigin, FieldAxesFollowTheAzimuth) {
  const GeoOrigin east{52.0, 0.5, 10.0, 90.0};  // x east, y north
  const GeoReference ref(east);
  const Wgs84 o = ref.to_wgs84({0, 0, 0});
  EXPECT_NEAR(o.latitude_deg, 52.0, 1e-12);
  EXPECT_NEAR(o.longitude_deg, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(o.altitude_m, 10.0);
  const Wgs84 x = ref.to_wgs84({100, 0, 1.5});
  EXPECT_NEAR(x.latitude_deg, 52.0, 1e-7);  // 100 m east stays on the parallel (to ~1 cm)
  EXPECT_NEAR((x.longitude_deg - 0.5) * metres_per_degree_longitude(52.0), 100.0, 0.01);
  EXPECT_DOUBLE_EQ(x.altitude_m, 11.5);
  const Wgs84 y = ref.to_wgs84({0, 100, 0});
  EXPECT_NEAR(y.longitude_deg, 0.5, 1e-12);
  EXPECT_NEAR((y.latitude_deg - 52.0) * metres_per_degree_latitude(52.0), 100.0, 0.01);

  const GeoReference north(GeoOrigin{52.0, 0.5, 0.0, 0.0});  // x north, y west
  const Wgs84 n = north.to_wgs84({100, 0, 0});
  EXPECT_NEAR((n.latitude_deg - 52.0) * metres_per_degree_latitude(52.0), 100.0, 0.01);
  const Wgs84 w = north.to_wgs84({0, 100, 0});
  EXPECT_NEAR((w.longitude_deg - 0.5) * metres_per_degree_longitude(52.0), -100.0, 0.01);
}

TEST(GeoOrigin, RoundTripIsExactToAMicrometre) {
  const GeoReference ref(GeoOrigin{-33.9, 151.2, 40.0, 37.5});
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(812.3, -402.1, 0.7), Eigen::Vector3d(-2000, 1500, -3)}) {
    const Eigen::Vector3d back = ref.to_field(ref.to_wgs84(p));
    EXPECT_LT((back - p).norm(), 1e-6) << p.transpose();
  }
}

TEST(GeoOrigin, FileRoundTripAndErrors) {
  cropsight::testing::TempDir tmp;
  const fs::path f = tmp.path() / "geo_origin.yaml";
  const GeoOrigin g{52.18342176, 0.1473, 12.25, 271.0};
  write_geo_origin(f, g);
  const GeoOrigin r = read_geo_origin(f);
  EXPECT_EQ(r.latitude_deg, g.latitude_deg);
  EXPECT_EQ(r.longitude_deg, g.longitude_deg);
  EXPECT_EQ(r.altitude_m, g.altitude_m);
  EXPECT_EQ(r.field_x_azimuth_deg, g.field_x_azimuth_deg);

  write_file_atomic(f, "latitude_deg: 52\nlongitude_deg: 1\n");
  EXPECT_EQ(read_geo_origin(f).field_x_azimuth_deg, 90.0);  // the documented default: x east
  EXPECT_EQ(read_geo_origin(f).altitude_m, 0.0);
  for (const char* bad : {"latitude_deg: 52\n", "latitude_deg: 95\nlongitude_deg: 1\n",
                          "latitude_deg: 52\nlongitude_deg: 1\nfield_x_azimuth_deg: 360\n",
                          "latitude_deg: 52\nlongitude_deg: 1\nheading: 3\n", "latitude_deg: [1]\nlongitude_deg: 1\n",
                          "latitude_deg: north\nlongitude_deg: 1\n", "- 1\n"}) {
    write_file_atomic(f, bad);
    try {
      read_geo_origin(f);
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), f.string()) << bad;
    }
  }
  EXPECT_FALSE(read_sequence_geo_origin(tmp.path() / "nothing").has_value());
}

}  // namespace geo_origin_test
}  // namespace cropsight::io
