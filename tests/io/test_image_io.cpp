#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

using testing::TempDir;
namespace fs = std::filesystem;

Image<std::uint16_t> ramp16(int w, int h) {
  Image<std::uint16_t> img(w, h);
  for (std::size_t i = 0; i < img.size(); ++i) img.data[i] = std::uint16_t(i * 997 % 65536);
  return img;
}

TEST(ImageIo, U16RoundTrip) {
  TempDir tmp;
  const auto img = ramp16(17, 9);
  write_u16(tmp / "a.png", img);
  EXPECT_EQ(read_u16(tmp / "a.png"), img);
}

TEST(ImageIo, ColorRoundTripKeepsChannelOrder) {
  TempDir tmp;
  ColorImage img(5, 4);
  for (int v = 0; v < 4; ++v)
    for (int u = 0; u < 5; ++u) img.at(u, v) = Rgb8{std::uint8_t(50 * u), std::uint8_t(60 * v), 7};
  write_color(tmp / "c.png", img);
  EXPECT_EQ(read_color(tmp / "c.png"), img);
  // OpenCV stores BGR: check the file really has red in the third channel, as other tools expect.
  const cv::Mat m = cv::imread((tmp / "c.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(m.at<cv::Vec3b>(0, 4)[2], 200);
}

TEST(ImageIo, GrayRoundTripAndExpansionToColor) {
  TempDir tmp;
  GrayImage g(6, 3);
  for (std::size_t i = 0; i < g.size(); ++i) g.data[i] = std::uint8_t(i * 13);
  write_gray(tmp / "g.png", g);
  EXPECT_EQ(read_gray(tmp / "g.png"), g);
  const ColorImage c = read_color(tmp / "g.png");
  EXPECT_EQ(c.at(2, 1), (Rgb8{g.at(2, 1), g.at(2, 1), g.at(2, 1)}));
}

TEST(ImageIo, EncodingIsDeterministic) {
  const auto img = ramp16(64, 48);
  EXPECT_EQ(encode_png(img), encode_png(img));
  TempDir tmp;
  write_u16(tmp / "a.png", img);
  write_u16(tmp / "b.png", img);
  EXPECT_EQ(read_file(tmp / "a.png"), read_file(tmp / "b.png"));
  EXPECT_EQ(read_file(tmp / "a.png"), encode_png(img));
}

void expect_error_names(const fs::path& path, const std::function<void()>& f, const std::string& words) {
  try {
    f();
    FAIL() << "no error for " << path;
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), path.string());
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(ImageIo, WrongBitDepthAndChannelsAreErrorsNamingTheFile) {
  TempDir tmp;
  GrayImage g(4, 4, 9);
  write_gray(tmp / "g8.png", g);
  expect_error_names(
      tmp / "g8.png", [&] { read_u16(tmp / "g8.png"); }, "8-bit");
  write_u16(tmp / "d16.png", ramp16(4, 4));
  expect_error_names(
      tmp / "d16.png", [&] { read_color(tmp / "d16.png"); }, "16-bit");
  expect_error_names(
      tmp / "d16.png", [&] { read_gray(tmp / "d16.png"); }, "16-bit");
  ColorImage c(4, 4);
  write_color(tmp / "c.png", c);
  expect_error_names(
      tmp / "c.png", [&] { read_u16(tmp / "c.png"); }, "3-channel");
  cv::Mat bgra(4, 4, CV_8UC4, cv::Scalar(1, 2, 3, 4));
  cv::imwrite((tmp / "bgra.png").string(), bgra);
  expect_error_names(
      tmp / "bgra.png", [&] { read_color(tmp / "bgra.png"); }, "4-channel");
}

TEST(ImageIo, MissingAndCorruptFiles) {
  TempDir tmp;
  expect_error_names(
      tmp / "none.png", [&] { read_u16(tmp / "none.png"); }, "not found");
  write_file_atomic(tmp / "bad.png", "not a png");
  expect_error_names(
      tmp / "bad.png", [&] { read_u16(tmp / "bad.png"); }, "decode");
  fs::create_directories(tmp / "dir.png");
  expect_error_names(
      tmp / "dir.png", [&] { read_u16(tmp / "dir.png"); }, "is a directory");
}

// Fuzzing finding 20: OpenCV decodes PFM, Radiance HDR and OpenEXR content only from a file, so
// cv::imdecode copied such bytes to a temporary file and, when the header was bad, left it behind
// (one stray /tmp/__opencv_temp.* per damaged image). OPENCV_TEMP_PATH points OpenCV's temporary
// files at a folder of this test's own (ctest runs each test in its own process).
TEST(ImageIo, ADamagedImageLeavesNoOpenCvTemporaryFile) {
  TempDir tmp;
  const fs::path opencv_tmp = tmp / "opencv_tmp";
  fs::create_directories(opencv_tmp);
  ASSERT_EQ(setenv("OPENCV_TEMP_PATH", opencv_tmp.c_str(), 1), 0);
  const std::string bad_pfm("Pf\n0 4\n-1\n\0\0 4\n-1\n\0~~~~~~~~~~~~~~~~", 30);
  write_file_atomic(tmp / "pfm.png", bad_pfm);
  expect_error_names(
      tmp / "pfm.png", [&] { read_u16(tmp / "pfm.png"); }, "decode");
  write_file_atomic(tmp / "hdr.png", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 99999999\n");
  expect_error_names(
      tmp / "hdr.png", [&] { read_color(tmp / "hdr.png"); }, "decode");
  // A well-formed PFM still decodes (and is refused for its depth, not its format).
  write_file_atomic(tmp / "good.png", std::string("Pf\n2 1\n-1\n", 10) + std::string(8, '\0'));
  expect_error_names(
      tmp / "good.png", [&] { read_u16(tmp / "good.png"); }, "32-bit");
  unsetenv("OPENCV_TEMP_PATH");
  EXPECT_TRUE(fs::is_empty(opencv_tmp)) << "OpenCV left " << fs::directory_iterator(opencv_tmp)->path();
}

// Fuzzing finding 29: Debian's OpenCV hands content with "DICM" at offset 128 to GDCM, which
// asserts (abort) on a damaged header. Only the formats cropsight reads are offered to OpenCV;
// anything else is one error naming the file, whatever its extension.
TEST(ImageIo, OnlyKnownImageFormatsReachOpenCv) {
  TempDir tmp;
  const std::string dicom =
      io::read_file(fs::path(CROPSIGHT_SOURCE_DIR) / "fuzz/regressions/stereo_ground_truth/crash-2d11e407b57f");
  ASSERT_EQ(dicom.substr(128, 4), "DICM");
  write_file_atomic(tmp / "dicom.png", dicom);
  expect_error_names(
      tmp / "dicom.png", [&] { read_u16(tmp / "dicom.png"); }, "not an image format cropsight reads");
  // Finding 31: a PFM-like start ("Pf" without the whitespace OpenCV's PFM check wants) with
  // "DICM" at 128 still reached GDCM; content that GDCM or GDAL would claim is refused first.
  const std::string pf_dicom =
      io::read_file(fs::path(CROPSIGHT_SOURCE_DIR) / "fuzz/regressions/stereo_ground_truth/crash-e5dec8fdaa8a");
  ASSERT_EQ(pf_dicom.substr(0, 2), "Pf");
  write_file_atomic(tmp / "pf.png", pf_dicom);
  expect_error_names(
      tmp / "pf.png", [&] { read_u16(tmp / "pf.png"); }, "not an image format cropsight reads");
  for (const std::string& gdal : {std::string("NITF02.10") + std::string(200, ' '),
                                  std::string("P5\n") + std::string(137, 'x') + "DTED" + std::string(40, 'x')}) {
    write_file_atomic(tmp / "gdal.png", gdal);
    expect_error_names(
        tmp / "gdal.png", [&] { read_u16(tmp / "gdal.png"); }, "not an image format cropsight reads");
  }
  write_file_atomic(tmp / "jp2.png", std::string("\0\0\0\x0cjP  \r\n\x87\n", 12) + std::string(40, 'x'));
  expect_error_names(
      tmp / "jp2.png", [&] { read_color(tmp / "jp2.png"); }, "not an image format cropsight reads");
  // Finding 33: a 30-byte P6 header claiming 244604 x 4024 pixels made OpenCV allocate 2.9 GB
  // before it found no data; the header's size is checked against the file first.
  const std::string huge_ppm =
      io::read_file(fs::path(CROPSIGHT_SOURCE_DIR) / "fuzz/regressions/stereo_ground_truth/oom-69a38a4d34a2");
  write_file_atomic(tmp / "huge.png", huge_ppm);
  expect_error_names(
      tmp / "huge.png", [&] { read_u16(tmp / "huge.png"); }, "truncated image");
  write_file_atomic(tmp / "short.pgm", std::string("P5\n# c\n4 4\n255\n") + std::string(15, 'x'));
  expect_error_names(
      tmp / "short.pgm", [&] { read_u16(tmp / "short.pgm"); }, "needs 16 bytes of pixels, the file has 15");
  write_file_atomic(tmp / "pam.png", std::string("P7\nWIDTH 9000\nHEIGHT 9000\nDEPTH 3\nMAXVAL 255\nENDHDR\n") + "xx");
  expect_error_names(
      tmp / "pam.png", [&] { read_color(tmp / "pam.png"); }, "truncated image");
  // The formats cropsight reads still decode, whatever the file is called.
  const cv::Mat grey(3, 4, CV_8UC1, cv::Scalar(7));
  for (const char* ext : {".png", ".bmp", ".tiff", ".pgm", ".jpg", ".webp"}) {
    std::vector<std::uint8_t> bytes;
    ASSERT_TRUE(cv::imencode(ext, grey, bytes)) << ext;
    write_file_atomic(tmp / "img.bin.png", std::string(bytes.begin(), bytes.end()));
    EXPECT_NO_THROW(read_color(tmp / "img.bin.png")) << ext;
  }
}

TEST(ImageIo, FailedWriteLeavesNothing) {
  TempDir tmp;
  EXPECT_THROW(write_u16(tmp / "noext", ramp16(3, 3)), Error);
  EXPECT_THROW(write_u16(tmp / "empty.png", Image<std::uint16_t>()), Error);
  EXPECT_TRUE(fs::is_empty(tmp.path()));
}

}  // namespace
}  // namespace cropsight::io
