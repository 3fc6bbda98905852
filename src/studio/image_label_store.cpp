// The label files of a folder of images labelled in the studio (studio/image_label_store.hpp).
#include "cropsight/studio/image_label_store.hpp"

#include <algorithm>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/io/file_names.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/studio/sequence_files.hpp"

namespace cropsight::studio {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarkerCommand = "studio";

// The marker's list of what an earlier studio wrote, after checking that the folder is one.
std::vector<std::string> earlier_outputs(const fs::path& out) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return {};
  if (!fs::is_directory(out, ec))
    throw Error(out.string(), "exists and is not a folder the studio wrote; move it away");
  const io::OutputMarker marker = io::read_output_marker(out);
  if (!marker.present || marker.command != kMarkerCommand)
    throw Error(out.string(), "exists and was not written by cropsight studio; move it away to label this folder");
  return marker.entries;
}

std::vector<std::string> image_names(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(dir.string(), "is not a folder of images");
  std::vector<std::string> names;
  std::set<std::string> stems;
  for (const fs::path& file : io::list_images(dir)) {
    const std::string name = file.filename().string();
    // Hidden names, and links that lead out of the folder, are not the folder's images: the
    // studio serves nothing outside the folder it was given, whatever the folder holds.
    if (!file_in_sequence(dir, name)) continue;
    if (!stems.insert(file.stem().string()).second)
      throw Error(file.string(), "another image has the stem '" + file.stem().string() +
                                     "' (its VOC and YOLO label files would be the same); rename one");
    names.push_back(name);
  }
  if (names.empty()) throw Error(dir.string(), "holds no .jpg or .png image");
  return names;
}

// One name a line (YOLO's classes.txt: line k is class k).
std::string lines(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += n + "\n";
  return text;
}

void add_class(std::vector<std::string>& classes, const std::string& name) {
  if (std::find(classes.begin(), classes.end(), name) == classes.end()) classes.push_back(name);
}

}  // namespace

ImageLabelStore::ImageLabelStore(fs::path dir, const std::vector<std::string>& classes, bool read_only)
    : dir_(std::move(dir)), names_(image_names(dir_)), read_only_(read_only) {
  const fs::path out = output_folder();
  written_ = earlier_outputs(out);
  for (const auto& c : classes) add_class(classes_, c);
  if (!fs::exists(out / "coco.json")) return;
  io::LabelSet set = io::read_coco_labels(out / "coco.json");
  for (const auto& c : set.classes) add_class(classes_, c);
  // Every image of it, also one no longer in the folder: a save rewrites coco.json, and must not
  // drop labels of an image the user moved away for a while.
  for (auto& image : set.images) saved_[image.file_name] = std::move(image);
}

std::vector<int> ImageLabelStore::labelled() const {
  std::lock_guard lock(mutex_);
  std::vector<int> out;
  for (std::size_t k = 0; k < names_.size(); ++k)
    if (saved_.count(names_[k])) out.push_back(int(k));
  return out;
}

std::vector<std::string> ImageLabelStore::classes() const {
  std::lock_guard lock(mutex_);
  return classes_;
}

std::optional<io::ImageLabels> ImageLabelStore::labels(int index) const {
  std::lock_guard lock(mutex_);
  const auto it = saved_.find(names_.at(std::size_t(index)));
  if (it == saved_.end()) return std::nullopt;
  return it->second;
}

std::pair<int, int> ImageLabelStore::size(int index) {
  {
    std::lock_guard lock(mutex_);
    if (const auto it = sizes_.find(index); it != sizes_.end()) return it->second;
  }
  const ColorImage image = io::read_color(image_path(index));  // outside the lock: a decode takes a while
  std::lock_guard lock(mutex_);
  return sizes_[index] = {image.width, image.height};
}

void ImageLabelStore::save(int index, std::vector<io::LabelShape> shapes) {
  if (read_only_) throw Error(dir_.string(), "opened read-only: labels are not written");
  const auto [width, height] = size(index);
  std::lock_guard lock(mutex_);
  // Kept to be put back should a write fail: the store then still says what the files hold.
  const auto classes_before = classes_;
  const auto saved_before = saved_;
  for (const auto& s : shapes) add_class(classes_, s.label);
  const std::string& name = names_.at(std::size_t(index));
  saved_[name] = io::ImageLabels{name, width, height, std::move(shapes)};
  try {
    write_outputs(index);
  } catch (...) {
    classes_ = classes_before;
    saved_ = saved_before;
    throw;
  }
}

void ImageLabelStore::write_outputs(int index) {
  const fs::path out = output_folder();
  const fs::path image = names_[std::size_t(index)];
  const std::string stem = image.stem().string();
  const io::ImageLabels& labels = saved_.at(image.string());
  io::LabelSet set{classes_, {}};
  for (const auto& name : names_)
    if (const auto it = saved_.find(name); it != saved_.end()) set.images.push_back(it->second);
  for (const auto& [name, image] : saved_)  // then those no longer in the folder
    if (std::find(names_.begin(), names_.end(), name) == names_.end()) set.images.push_back(image);
  const std::vector<std::pair<std::string, std::string>> files = {
      {"voc/" + stem + ".xml", io::voc_xml(labels)},
      {"yolo/" + stem + ".txt", io::yolo_text(labels, classes_)},
      {"yolo/classes.txt", lines(classes_)},
      {"coco.json", io::coco_json(set)}};
  // Every file first checked: one the marker does not list and that exists is a user's.
  std::error_code ec;
  for (const auto& [relative, text] : files)
    if (std::find(written_.begin(), written_.end(), relative) == written_.end() && fs::exists(out / relative, ec))
      throw Error((out / relative).string(), "exists and was not written by the studio; move it away");
  fs::create_directories(out);
  for (const auto& [relative, text] : files) {
    if (std::find(written_.begin(), written_.end(), relative) == written_.end()) {
      // Listed before the file exists: a kill in between leaves a listed name without a file,
      // never a file of ours the next studio would take for the user's.
      for (const std::string& folder : {std::string("voc"), std::string("yolo")})
        if (relative.rfind(folder + "/", 0) == 0 &&
            std::find(written_.begin(), written_.end(), folder) == written_.end())
          written_.push_back(folder);
      written_.push_back(relative);
      io::write_output_marker(out, kMarkerCommand, written_);
    }
    io::write_file_atomic(out / relative, text);
  }
}

}  // namespace cropsight::studio
