#pragma once
// Internal: a zip archive's structure and checksums checked before another library reads it.
// libtorch's archives (.pt: network models and checkpoints) are zip files of stored entries;
// libtorch 1.13 does not verify their CRC-32s, and its TorchScript parser crashed (SIGSEGV) on a
// damaged one (fuzz_network_archive; fuzz/regressions/network_archive/). Every entry of the
// central directory must lie inside the file, be stored or deflated (libtorch deflates its
// TorchScript code and stores the tensors) and match its CRC-32 after inflating, so a truncated or bit-flipped model
// file is an Error instead of a crash. This catches damage, not a file crafted to pass the checks.
#include <filesystem>
#include <string>

namespace cropsight::io::detail {

/// Throws Error(where, ...) naming the first problem of zip archive contents `bytes`.
void check_zip(const std::string& bytes, const std::string& where);

}  // namespace cropsight::io::detail
