#pragma once
// Where an installed (or built) cropsight finds its own files: the shipped presets and models.
// Never through the source tree it was built from, so that a build or an install moved to another
// folder or machine keeps working, and no path of the build machine is compiled into a binary.
//
// Layout, the same in an install prefix and in a build tree (which mirrors it with links):
//   PREFIX/bin/cropsight           the programs (the CLI, ROS nodes, tests in a build tree)
//   PREFIX/lib/                    the libtorch plugin
//   PREFIX/share/cropsight/configs the presets   (configs/ of the source tree)
//   PREFIX/share/cropsight/models  the models    (models/ of the source tree)
// Thread-safe: reads the environment and /proc only.
#include <filesystem>

namespace cropsight {

/// The folder of the running program (/proc/self/exe, links resolved); empty when unknown.
std::filesystem::path executable_dir();

/// cropsight's data folder (the one holding configs/ and models/): $CROPSIGHT_DATA_DIR when set,
/// else PROGRAM/../share/cropsight when it exists, else empty (a program outside an install, e.g.
/// a library consumer's own, then names presets and models by path or sets the variable).
std::filesystem::path data_dir();

}  // namespace cropsight
