// The body of a studio label save (POST /api/frame/N/labels, src/studio/pixel_runs.hpp): any
// bytes give heads inside the frame or an error, never a crash or an allocation beyond the bound.
#include <cstddef>
#include <cstdint>
#include <string>

#include "studio/pixel_runs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr int kPixels = 64 * 48;
  std::string error;
  const auto heads =
      cropsight::studio::parse_heads_body(std::string(reinterpret_cast<const char*>(data), size), kPixels, error);
  if (heads) {
    std::size_t total = 0;
    for (const auto& head : *heads) {
      for (int p : head)
        if (p < 0 || p >= kPixels) __builtin_trap();
      total += head.size();
    }
    if (total > 4 * std::size_t(kPixels)) __builtin_trap();
  } else if (error.empty()) {
    __builtin_trap();
  }
  return 0;
}
