#pragma once
// `cropsight import --coco FILE | --labelme DIR | --cvat FILE`: other tools' image labels into what
// our trainers read (io/image_labels.hpp). With --data SEQ (a depth sequence) a new sequence of the
// labelled frames with labels/ instance PNGs; without it COCO JSON, YOLO txt or VOC XML.
#include <CLI/CLI.hpp>
#include <string>

namespace cropsight::cli {

struct LabelImportOptions {
  std::string coco, labelme, cvat;  ///< exactly one names the labels to import
  std::string to = "coco";          ///< image sets: coco | yolo | voc
  std::string classes;              ///< comma list: only these labels ("" = every one)
  bool given() const { return !coco.empty() || !labelme.empty() || !cvat.empty(); }
};

void add_label_import_options(CLI::App* cmd, LabelImportOptions& o);

/// Imports the labels; `sequence` is --data (a sequence folder, or "" for an image set). Throws
/// Error naming the file or option; writes nothing on a bad input.
void run_label_import(const LabelImportOptions& o, const std::string& sequence, const std::string& out, bool force,
                      bool json);

}  // namespace cropsight::cli
