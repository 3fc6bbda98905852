#include "fuzz_support.hpp"

#include <unistd.h>

#include <fstream>
#include <system_error>

namespace cropsight::fuzz {
namespace {

// Owns the folder so that it goes when the fuzzer exits normally (a crash leaves it in $TMPDIR,
// beside the saved input, which helps reproduce it).
struct Scratch {
  std::filesystem::path dir;
  Scratch() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/cropsight-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) {
      std::perror("cropsight fuzz: mkdtemp");
      std::abort();
    }
    dir = pattern;
    // OpenCV's temporary files (cv::imdecode of formats it reads only from files) go here, so
    // that one left behind is seen (expect_error_or_success; finding 20).
    std::filesystem::create_directories(dir / "opencv_tmp");
    setenv("OPENCV_TEMP_PATH", (dir / "opencv_tmp").c_str(), 1);
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

}  // namespace

const std::filesystem::path& scratch_dir() {
  static Scratch scratch;  // one per process: the harness's working folder
  return scratch.dir;
}

std::filesystem::path write_input(std::string_view bytes, const std::string& name) {
  const std::filesystem::path path = scratch_dir() / name;
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) {
    std::fprintf(stderr, "cropsight fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

void expect_no_stray_files(const char* what) {
  const std::filesystem::path opencv_tmp = scratch_dir() / "opencv_tmp";
  std::error_code ec;
  std::filesystem::directory_iterator it(opencv_tmp, ec);
  if (!ec && it != std::filesystem::directory_iterator()) {
    std::fprintf(stderr, "%s: left OpenCV's temporary file %s behind\n", what, it->path().c_str());
    std::abort();
  }
}

void remove_input(const std::string& name) {
  std::error_code ec;
  std::filesystem::remove_all(scratch_dir() / name, ec);
}

}  // namespace cropsight::fuzz
