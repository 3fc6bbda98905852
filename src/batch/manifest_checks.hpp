#pragma once
// The checks every manifest format shares (manifest.cpp: YAML; manifest_csv.cpp: CSV), so that a
// recording, a crop or a pipeline is judged the same way whichever file named it.
#include <filesystem>
#include <string>

#include "cropsight/batch/manifest.hpp"

namespace cropsight::batch::detail {

/// Sets m.crop; Error(where, ...) when empty or not a crop batches run.
void set_crop(Manifest& m, const std::string& where, const std::string& crop);

/// A model, preset or detector as written in a manifest in `folder` (absolute): a file (relative
/// to the manifest or absolute) becomes absolute; anything else (a shipped name) stays as written.
std::string file_or_name(const std::filesystem::path& folder, const std::string& value);

/// Adds the recording `text` (relative to `folder` or absolute) to m.recordings after opening it
/// as m.crop reads recordings (m.crop must be set). Error(where, ...) for a missing recording,
/// Error(file inside it, ...) for a malformed one.
void add_recording(Manifest& m, const std::string& where, const std::string& text, const std::filesystem::path& folder);

/// Error(where, ...) unless the recordings have distinct folder names (each names its shards).
void check_distinct_names(const Manifest& m, const std::string& where);

/// Builds the pipeline once as every shard will (crop_shards.hpp); Error(where, "pipeline: ...").
void check_pipeline(const Manifest& m, const std::string& where);

}  // namespace cropsight::batch::detail
