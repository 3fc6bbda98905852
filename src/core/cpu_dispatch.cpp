#include "core/cpu_dispatch.hpp"

namespace cropsight::detail {

bool cpu_has_avx2_fma() {
#if CROPSIGHT_X86_DISPATCH
  static const bool ok =
      __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("popcnt");
  return ok;
#else
  return false;
#endif
}

}  // namespace cropsight::detail
