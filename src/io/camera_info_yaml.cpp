// ROS camera_info YAML -> CameraIntrinsics. Two spellings exist in the wild: camera_calibration's
// file (the one camera drivers load through camera_info_manager) and the message as `rostopic
// echo` prints it; both carry the same K, D and size under different keys.
#include "camera_info_yaml.hpp"

#include <vector>

#include "cropsight/core/error.hpp"
#include "number_text.hpp"

namespace cropsight::io::detail {

namespace {

std::vector<double> number_list(const YAML::Node& node, const std::string& key, const std::string& where) {
  if (!node || !node.IsSequence()) throw Error(where, "'" + key + "' must be a list of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const auto v = node[i].IsScalar() ? parse_double(node[i].Scalar()) : std::nullopt;
    if (!v) throw Error(where, "'" + key + "' must be a list of finite numbers");
    out.push_back(*v);
  }
  return out;
}

// camera_calibration writes matrices as {rows, cols, data}; the data is what we need.
std::vector<double> matrix_data(const YAML::Node& root, const std::string& key, const std::string& where) {
  const YAML::Node m = root[key];
  if (!m) throw Error(where, "missing required key '" + key + "'");
  if (!m.IsMap()) throw Error(where, "'" + key + "' must be a mapping with rows, cols and data");
  return number_list(m["data"], key + ".data", where);
}

int positive_int(const YAML::Node& root, const std::string& key, const std::string& where) {
  const YAML::Node n = root[key];
  if (!n) throw Error(where, "missing required key '" + key + "'");
  const auto v = n.IsScalar() ? parse_int(n.Scalar()) : std::nullopt;
  if (!v || *v <= 0 || *v > 100000) throw Error(where, "'" + key + "' must be a positive integer");
  return int(*v);
}

}  // namespace

CameraFileKind camera_file_kind(const YAML::Node& root) {
  if (!root.IsMap()) return CameraFileKind::Unknown;
  if (root["camera_matrix"] || root["image_width"] || root["image_height"]) return CameraFileKind::RosCalibration;
  if (root["K"]) return CameraFileKind::RosMessage;
  for (const char* key : {"width", "height", "fx", "fy", "cx", "cy", "depth_scale"})
    if (root[key]) return CameraFileKind::Cropsight;
  return CameraFileKind::Unknown;
}

const char* accepted_camera_files() {
  return "not a camera file: expected a YAML mapping, either cropsight's camera.yaml (width, height, fx, fy, cx, cy, "
         "depth_scale), "
         "a ROS camera_info YAML (image_width, image_height, camera_matrix, distortion_coefficients) or a "
         "CameraInfo message as rostopic echo prints it (width, height, K, D); docs/formats.md";
}

CameraIntrinsics camera_from_ros_yaml(const YAML::Node& root, CameraFileKind kind, const std::string& where) {
  const bool calibration = kind == CameraFileKind::RosCalibration;
  CameraIntrinsics c;
  c.width = positive_int(root, calibration ? "image_width" : "width", where);
  c.height = positive_int(root, calibration ? "image_height" : "height", where);
  const std::vector<double> k =
      calibration ? matrix_data(root, "camera_matrix", where) : number_list(root["K"], "K", where);
  if (k.size() != 9) throw Error(where, "the camera matrix must have 9 numbers (3x3), got " + std::to_string(k.size()));
  c.fx = k[0];
  c.cx = k[2];
  c.fy = k[4];
  c.cy = k[5];
  const YAML::Node model = root["distortion_model"];
  const std::string model_name = model && model.IsScalar() ? model.Scalar() : "";
  const YAML::Node d = calibration ? root["distortion_coefficients"] : root["D"];
  if (d) c.distortion = calibration ? matrix_data(root, "distortion_coefficients", where) : number_list(d, "D", where);
  // plumb_bob and rational_polynomial list k1 k2 p1 p2 k3 [k4 k5 k6] as OpenCV does; equidistant
  // (fisheye) coefficients mean something else, and a silently wrong model is worse than none.
  if (!c.distortion.empty() && model_name != "plumb_bob" && model_name != "rational_polynomial")
    throw Error(where, "distortion_model '" + model_name + "' is not supported (plumb_bob, rational_polynomial)");
  if (const YAML::Node name = root["camera_name"]; name && name.IsScalar()) c.sensor = name.Scalar();
  c.depth_scale = 0.001;  // REP 118: 16-bit depth images are millimetres
  c.validate(where);
  return c;
}

}  // namespace cropsight::io::detail
