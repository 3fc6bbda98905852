#pragma once
// The one rule for everything cropsight writes: a command never deletes or overwrites what it did
// not write. Every writer (CLI commands, tools, the simulator, the bag writer) checks its outputs
// with these calls before any work, so a bad --out costs no run:
//
// - an output (file or folder) equal to, inside, or containing one of the command's inputs is
//   refused, whatever --force says;
// - an output folder must be new, empty, or one cropsight wrote: it then carries the marker file
//   `.cropsight-output`, which names the command and lists every file the command wrote. --force
//   allows replacing such a folder, and only while it holds nothing but the listed files (a user's
//   note added to an output folder later makes it refused again);
// - an output file that exists is replaced only with --force: a file is one path the user named
//   on the command line, so --force is consent for exactly that file. A folder is never replaced
//   in place of a file, nor a file in place of a folder;
// - the location is proven writable before the work (a probe file is created and removed, or the
//   output folder's temporary is made), and
//   the output is written under a temporary name and renamed when complete (files.hpp).
//
// Paths are compared after resolving symbolic links and `..` (std::filesystem::weakly_canonical),
// so `out`, `./out/` and a link to it are one path. Every refusal is an Error naming the output
// path; the CLI prints it as one line and exits 2. Nothing here holds global state; an
// OutputFolder is used by one thread.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/io/files.hpp"

namespace cropsight::io {

/// The marker's file name, inside every output folder cropsight writes. The sequence reader and
/// every folder reader skip names that start with '.'.
inline constexpr const char* kOutputMarker = ".cropsight-output";

/// What a command reads and whether it may replace a previous cropsight output; every output of
/// the command is checked against it.
struct OutputPolicy {
  std::string command;                        ///< e.g. "detect potato": written into the marker
  bool force = false;                         ///< --force: a previous cropsight output may be replaced
  std::vector<std::filesystem::path> inputs;  ///< files and folders the command reads (empty ones ignored)
};

/// The marker of `dir`: whether it exists, the command that wrote it and the files it lists
/// (paths relative to `dir`, folders included). `present` is false when `dir` has no marker or
/// the marker cannot be read as one.
struct OutputMarker {
  bool present = false;
  std::string command;
  std::vector<std::string> entries;
};
OutputMarker read_output_marker(const std::filesystem::path& dir);

/// Writes `dir`'s marker naming `command` and listing `entries` (paths relative to `dir`, folders
/// included: what the command wrote), for an output folder that is filled in place step by step
/// instead of written whole (a resumable batch: each step is its own atomic folder or file); call
/// it again after each step. Throws Error(dir, ...).
void write_output_marker(const std::filesystem::path& dir, const std::string& command,
                         const std::vector<std::string>& entries);

/// Throws Error(out, ...) when `out` is one of `policy.inputs`, lies inside one, or contains one.
void check_not_an_input(const std::filesystem::path& out, const OutputPolicy& policy);

/// Checks a file output before the work: not an input (check_not_an_input), not an existing
/// folder, replaced only with --force when it exists, and creatable (a probe file is created and
/// removed in the nearest existing folder above it). Creates nothing that stays. Throws
/// Error(file, ...).
void check_output_file(const std::filesystem::path& file, const OutputPolicy& policy);

/// Checks a folder output before the work (the rules at the top of this header) and proves its
/// parent writable. Creates nothing that stays. Throws Error(dir, ...).
void check_output_folder(const std::filesystem::path& dir, const OutputPolicy& policy);

/// An output folder written whole: the constructor checks `dir` by the rules of
/// check_output_folder and makes an empty temporary sibling to write into (which proves the parent
/// writable); commit() writes the marker (listing every file then in the temporary) and puts the
/// temporary in place of `dir` in one step (replace_directory). Until then `dir` is untouched, and
/// the destructor removes the temporary (and any parent folders the constructor had to create), so
/// a failed or interrupted run leaves nothing behind. Use from one thread.
class OutputFolder {
 public:
  OutputFolder(const std::filesystem::path& dir, const OutputPolicy& policy);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// The temporary folder to write into.
  const std::filesystem::path& path() const { return tmp_; }
  /// The final folder.
  const std::filesystem::path& final_path() const { return dir_; }
  /// Writes the marker and moves the temporary in place of the final folder. `what` names the
  /// output in an error ("masks", "sequence"). Checks again that a folder that appeared at the
  /// final name meanwhile may be replaced.
  void commit(const std::string& what = "output folder");

 private:
  std::filesystem::path dir_, tmp_, created_parent_;
  OutputPolicy policy_;
  bool committed_ = false;
};

/// The absolute, normalised form of `path` without a trailing separator ("out/" → "/cwd/out"),
/// symbolic links of its existing part resolved. What every check above compares.
std::filesystem::path resolved_path(const std::filesystem::path& path);

}  // namespace cropsight::io
