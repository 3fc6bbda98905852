// import --coco / --labelme / --cvat (import_labels_cli.hpp): reads the labels whole, checks them
// against the sequence or the output format, then writes one output under a temporary name.
#include "import_labels_cli.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

#include "cli_common.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_labels.hpp"

namespace cropsight::cli {

namespace import_labels_cmd {
namespace fs = std::filesystem;

// The labels of the one source option given, and that option's path.
std::pair<io::LabelSet, std::string> read_labels(const LabelImportOptions& o) {
  if (int(!o.coco.empty()) + int(!o.labelme.empty()) + int(!o.cvat.empty()) != 1)
    throw Error("--coco/--labelme/--cvat", "give exactly one of them");
  if (!o.coco.empty()) return {io::read_coco_labels(o.coco), o.coco};
  if (!o.labelme.empty()) return {io::read_labelme_labels(o.labelme), o.labelme};
  return {io::read_cvat_labels(o.cvat), o.cvat};
}

// Keeps the shapes of `classes` (and those classes, in the order given).
void keep_classes(io::LabelSet& set, const std::vector<std::string>& classes) {
  if (classes.empty()) return;
  for (auto& im : set.images)
    std::erase_if(im.shapes, [&](const io::LabelShape& s) {
      return std::find(classes.begin(), classes.end(), s.label) == classes.end();
    });
  set.classes = classes;
}

void write_image_set(const io::LabelSet& set, const LabelImportOptions& o, const io::OutputPolicy& policy,
                     const std::string& out) {
  if (o.to == "coco") {
    io::check_output_file(out, policy);
    io::write_file_atomic(out, io::coco_json(set));
    return;
  }
  io::OutputFolder folder(out, policy);  // removed unless committed: a refusal below leaves nothing
  std::set<std::string> stems;
  for (const auto& im : set.images) {
    const std::string stem = fs::path(im.file_name).stem().string();
    if (!stems.insert(stem).second)
      throw Error(im.file_name, "a second image named '" + stem + "': " + o.to + " writes one file per image name");
    if (o.to == "yolo")
      io::write_file_atomic(folder.path() / (stem + ".txt"), io::yolo_text(im, set.classes));
    else
      io::write_file_atomic(folder.path() / (stem + ".xml"), io::voc_xml(im));
  }
  if (o.to == "yolo") {
    std::string names;
    for (const auto& c : set.classes) names += c + "\n";
    io::write_file_atomic(folder.path() / "classes.txt", names);
  }
  folder.commit(o.to + " labels");
}
}  // namespace import_labels_cmd

void add_label_import_options(CLI::App* cmd, LabelImportOptions& o) {
  cmd->add_option("--coco", o.coco, "Image labels to import: a COCO instances JSON (boxes, polygons)");
  cmd->add_option("--labelme", o.labelme, "Image labels to import: a folder of labelme JSON files");
  cmd->add_option("--cvat", o.cvat, "Image labels to import: a CVAT for images 1.1 XML file");
  cmd->add_option("--to", o.to,
                  "Labels of an image set (no --data) become: coco (a .json file), yolo or voc (a folder)")
      ->check(CLI::IsMember({"coco", "yolo", "voc"}))
      ->capture_default_str();
  cmd->add_option("--classes", o.classes, "Import only these labels (comma list; default every label)");
}

void run_label_import(const LabelImportOptions& o, const std::string& sequence, const std::string& out, bool force,
                      bool json) {
  using namespace import_labels_cmd;
  auto [set, source] = read_labels(o);
  const std::vector<std::string> classes =
      o.classes.empty() ? std::vector<std::string>{} : split_list(o.classes, "--classes");
  const io::OutputPolicy policy = output_policy("import", force, {source, sequence});
  nlohmann::json j{{"out", out}, {"images", set.images.size()}};
  if (!sequence.empty()) {
    if (o.to != "coco") throw Error("--to", "applies to image sets; with --data the output is a sequence");
    const auto s = io::write_labelled_sequence(sequence, set, classes, out, policy, source);
    j["frames"] = s.frames;
    j["instances"] = s.instances;
    j["source_frames"] = s.source_frames;
    if (!json)
      std::printf("wrote %s: %d labelled frames of %s, %d instances\n", out.c_str(), s.frames, sequence.c_str(),
                  s.instances);
  } else {
    keep_classes(set, classes);
    write_image_set(set, o, policy, out);
    j["format"] = o.to;
    j["classes"] = set.classes;
    if (!json)
      std::printf("wrote %s: %s labels of %zu images, %zu classes\n", out.c_str(), o.to.c_str(), set.images.size(),
                  set.classes.size());
  }
  if (json) print_json(j);
}

}  // namespace cropsight::cli
