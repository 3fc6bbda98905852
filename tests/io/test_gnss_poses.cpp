// GNSS fixes (CSV, NMEA GGA/RMC) to a local field frame and its geo origin.
#include "cropsight/io/gnss_poses.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace gnss_poses_test {

// An NMEA sentence with its checksum.
std::string sentence(const std::string& body) {
  unsigned sum = 0;
  for (char c : body) sum ^= static_cast<unsigned char>(c);
  char buf[8];
  std::snprintf(buf, sizeof buf, "*%02X", sum);
  return "$" + body + buf + "\r\n";
}

TEST(GnssPoses, CsvTrackAlongARowBecomesFieldX) {
  // A pass driving 30 m north-east (azimuth 45°): the local frame's x follows it.
  const GeoReference truth(GeoOrigin{52.2, 0.12, 10.0, 45.0});
  std::string csv = "timestamp,lat,lon,alt\n";
  for (int i = 0; i <= 30; ++i) {
    const Wgs84 w = truth.to_wgs84({double(i), 0.0, 0.5});
    char line[128];
    std::snprintf(line, sizeof line, "%.2f,%.10f,%.10f,%.3f\n", 100.0 + 0.1 * i, w.latitude_deg, w.longitude_deg,
                  w.altitude_m);
    csv += line;
  }
  cropsight::testing::TempDir tmp;
  write_file_atomic(tmp / "gnss.csv", csv);
  const LocalTrack t = gnss_to_local(read_gnss_fixes(tmp / "gnss.csv"));
  EXPECT_NEAR(t.origin.field_x_azimuth_deg, 45.0, 1e-4);
  ASSERT_EQ(t.positions.size(), 31u);
  EXPECT_NEAR(t.positions[30].x(), 30.0, 0.002);
  EXPECT_NEAR(t.positions[30].y(), 0.0, 0.002);
  EXPECT_NEAR(t.positions[30].z(), 0.0, 1e-9);  // the origin's altitude is the first fix's
  EXPECT_DOUBLE_EQ(t.timestamps[1], 100.1);
  EXPECT_NEAR(gnss_to_local(read_gnss_fixes(tmp / "gnss.csv"), 90.0).positions[30].x(), 30.0 * std::sqrt(0.5), 0.002);

  for (const char* bad : {"time,lat,lon\n1,52,0\n", "timestamp,lat,lon\n1,52\n", "timestamp,lat,lon\n1,95,0\n",
                          "timestamp,lat,lon\n2,52,0\n1,52,0\n", "timestamp,lat,lon\n"}) {
    write_file_atomic(tmp / "bad.csv", bad);
    EXPECT_THROW(read_gnss_fixes(tmp / "bad.csv"), Error) << bad;
  }
}

TEST(GnssPoses, NmeaGgaAndRmcWithChecksumsAndHemispheres) {
  std::string log = sentence("GPRMC,120000.00,A,5212.0000,N,00007.2000,W,0.6,45.0,071226,,,A");
  log += sentence("GPGGA,120000.00,5212.0000,N,00007.2000,W,4,12,0.8,15.5,M,45.1,M,,");
  log += sentence("GNGGA,120001.00,5212.0006,N,00007.2000,W,4,12,0.8,15.6,M,45.1,M,,");
  log += sentence("GPGGA,120002.00,5212.0012,N,00007.2000,W,0,00,,,M,,M,,");           // no fix: skipped
  log += "$GPGGA,120003.00,5212.0018,N,00007.2000,W,4,12,0.8,15.7,M,45.1,M,,*00\r\n";  // bad checksum
  log += sentence("GPGSV,3,1,12,01,40,083,46");                                        // ignored
  log += sentence("G,1,2,3") + sentence("GPGGAX,1,2,3");  // no sentence type we read: skipped
  cropsight::testing::TempDir tmp;
  write_file_atomic(tmp / "pass.nmea", log);
  const auto fixes = read_gnss_fixes(tmp / "pass.nmea");
  ASSERT_EQ(fixes.size(), 2u);
  EXPECT_NEAR(fixes[0].position.latitude_deg, 52.2, 1e-12);
  EXPECT_NEAR(fixes[0].position.longitude_deg, -0.12, 1e-12);
  EXPECT_DOUBLE_EQ(fixes[0].position.altitude_m, 15.5);  // GGA's, though RMC came first
  // 2026-12-07 12:00:00 UTC in seconds since 1970.
  EXPECT_DOUBLE_EQ(fixes[0].timestamp, 1796644800.0);
  EXPECT_DOUBLE_EQ(fixes[1].timestamp - fixes[0].timestamp, 1.0);
  const LocalTrack t = gnss_to_local(fixes);
  EXPECT_NEAR(t.origin.field_x_azimuth_deg, 0.0, 1e-6);  // drove north
  EXPECT_NEAR(t.positions[1].x(), 0.0006 / 60 * 111257.0, 0.05);
  write_file_atomic(tmp / "none.nmea", sentence("GPGGA,120002.00,5212.0012,N,00007.2000,W,0,00,,,M,,M,,"));
  EXPECT_THROW(read_gnss_fixes(tmp / "none.nmea"), Error);
}

}  // namespace gnss_poses_test
}  // namespace cropsight::io
