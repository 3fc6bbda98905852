#pragma once
// Internal to io: a PLY file checked before PCL reads it. Debian's PCL 1.13 keeps its asserts,
// and PLYReader asserts (aborting the program) on header lines it half-understands and on
// vertex data that disagrees with the header (fuzz_ply; fuzz/regressions/ply/). So the header
// grammar is checked strictly (ply, format, element, property and property list lines with
// exactly their tokens; comment/obj_info), and the data is walked once: a binary body must hold
// every element's values, an ascii body one line per element instance with exactly its values.
#include <string>

namespace cropsight::io::detail {

/// Throws Error(where, ...) naming the first problem of PLY file contents `bytes`.
void check_ply(const std::string& bytes, const std::string& where);

}  // namespace cropsight::io::detail
