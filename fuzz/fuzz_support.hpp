#pragma once
// What every libFuzzer harness (fuzz/fuzz_*.cpp) shares. The parsers under test take
// file paths, as the CLI gives them, so a harness writes the fuzzer's bytes to a file in a
// scratch folder of its own process and calls the parser on that path.
//
// The contract a harness checks, beyond ASan/UBSan's: the parser either succeeds or throws
// cropsight::Error (which the CLI prints as one line "FILE: PROBLEM" and exits 2 with). Any other
// exception would reach the CLI as exit 1 "internal error", so it is a finding: the harness prints
// it and aborts, and libFuzzer saves the input. So is a temporary file OpenCV leaves behind
// (finding 20: bad input must leave nothing).
//
// Not thread-safe: libFuzzer runs a harness on one thread.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <typeinfo>

#include "cropsight/core/error.hpp"

namespace cropsight::fuzz {

/// The process's scratch folder (created on first use under $TMPDIR, removed at exit).
const std::filesystem::path& scratch_dir();

/// Writes `bytes` to scratch_dir()/`name` (sub-folders created) and returns the path.
std::filesystem::path write_input(std::string_view bytes, const std::string& name);
inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  return write_input(std::string_view(reinterpret_cast<const char*>(data), size), name);
}

/// Removes scratch_dir()/`name` (a file or a folder) when it exists.
void remove_input(const std::string& name);

/// Aborts, naming `what`, when the parser left a temporary file of OpenCV's in the scratch
/// folder (scratch_dir() points $OPENCV_TEMP_PATH there): bad input must leave nothing behind.
void expect_no_stray_files(const char* what);

/// Runs `parse()`: returns normally when it succeeds or throws cropsight::Error; aborts on any
/// other exception after printing `what`, its type and message, and on a stray temporary file.
template <typename F>
void expect_error_or_success(const char* what, F&& parse) {
  struct CheckAfter {
    const char* what;
    ~CheckAfter() { expect_no_stray_files(what); }
  } check_after{what};
  try {
    parse();
    if (std::getenv("CROPSIGHT_FUZZ_VERBOSE")) std::fprintf(stderr, "%s: ok\n", what);
  } catch (const cropsight::Error& e) {
    // The documented outcome for bad input; CROPSIGHT_FUZZ_VERBOSE=1 shows it (checking seeds).
    if (std::getenv("CROPSIGHT_FUZZ_VERBOSE")) std::fprintf(stderr, "%s: Error: %s\n", what, e.what());
    return;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: escaped %s: %s\n", what, typeid(e).name(), e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "%s: escaped a non-std exception\n", what);
    std::abort();
  }
}

}  // namespace cropsight::fuzz
