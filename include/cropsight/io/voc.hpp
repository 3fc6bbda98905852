#pragma once
// Pascal VOC XML annotations and the potato paper's detection text files.
//
// VOC: <annotation> with <filename>, <size> (width, height, depth) and one <object> per box
// (<name>, optional <difficult>, <bndbox> with xmin, ymin, xmax, ymax). Coordinates are pixels as
// the labelling tool wrote them (the potato set: integers, corners inclusive, as pascalvoc.py of
// rafaelpadilla/Object-Detection-Metrics reads them); they are kept as written, never shifted.
//
// Detection text (one file per image, `<stem>.txt`): one box per line, "potato score x1 y1 x2 y2"
// (class name, confidence, corners in pixels), whitespace separated; blank lines are allowed.
// Scores and corners are read as double so that a ranking by score is the one Python's float
// gives on the same file (a float would merge scores that differ in the 8th digit).
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/core/detection2d.hpp"

namespace cropsight::io {

/// One annotated box of a VOC file (pixels, as written).
struct VocObject {
  std::string name;
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  bool difficult = false;  ///< <difficult>1</difficult>; absent = false
};

struct VocAnnotation {
  std::string filename;                  ///< <filename> (may be empty when the file has none)
  int width = 0, height = 0, depth = 0;  ///< <size>; 0 where absent
  std::vector<VocObject> objects;
};

/// Parses a VOC file. Throws Error(path, ...) naming the element for malformed XML, a missing
/// or non-numeric coordinate, xmax < xmin or ymax < ymin, or a root that is not <annotation>.
VocAnnotation read_voc(const std::filesystem::path& path);

/// One line of a detection text file.
struct DetectionLine {
  std::string label;
  double score = 0, x1 = 0, y1 = 0, x2 = 0, y2 = 0;
};

/// Reads a detection file strictly: every non-blank line has exactly six fields, a label and
/// five finite numbers, with x2 >= x1 and y2 >= y1. Throws Error(path, "line N: ...").
std::vector<DetectionLine> read_detection_text(const std::filesystem::path& path);

/// The text of `dets` in the paper's format (label = class_names[class_id], or "class<id>" when
/// out of range); scores with 8 significant digits, corners with 6.
std::string format_detection_text(const std::vector<Detection2D>& dets, const std::vector<std::string>& class_names);

/// Writes format_detection_text atomically (temporary name, then rename).
void write_detection_text(const std::filesystem::path& path, const std::vector<Detection2D>& dets,
                          const std::vector<std::string>& class_names);

}  // namespace cropsight::io
