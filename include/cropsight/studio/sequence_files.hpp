#pragma once
// Which files of a sequence the studio serves: a relative path that stays inside the sequence
// folder once `..`, symbolic links and percent-escapes are resolved, and names a regular file.
#include <filesystem>
#include <optional>
#include <string_view>

namespace cropsight::studio {

/// The file `relative` names inside `root` (a sequence folder), or nothing when it is empty,
/// absolute, holds a `..` or `.` segment, a backslash or a NUL, leads outside `root` through a
/// symbolic link, or is not a regular file. `relative` is the request path after URL decoding
/// (the server decodes once; a second level of escapes such as `%252e` stays literal and so names
/// no file). Hidden entries (a segment starting with '.', e.g. the studio's lock) are refused too.
std::optional<std::filesystem::path> file_in_sequence(const std::filesystem::path& root, std::string_view relative);

}  // namespace cropsight::studio
