// cropsight._import_bag: a ROS bag's depth, camera info and colour into a sequence folder
// (ros/include/cropsight_ros/bag_io.hpp), for cropsight.read_bag (python/cropsight/_bags.py), which
// owns the temporary folder. Without ROS (-DCROPSIGHT_ROS=OFF or no ROS packages) it raises
// cropsight.Error saying so, as the CLI's --data FILE.bag does.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "cropsight/core/error.hpp"
#ifdef CROPSIGHT_HAS_ROS
#include "cropsight_ros/bag_io.hpp"
#endif

namespace cropsight::python {

void bind_bags(py::module_& m) {
  m.def(
      "_import_bag",
      [](const std::string& bag, const std::string& out, const std::string& depth_topic, const std::string& info_topic,
         const std::string& color_topic) {
#ifdef CROPSIGHT_HAS_ROS
        ros_io::BagImportOptions o;
        o.bag = bag;
        o.out = out;
        o.topics.depth = depth_topic;
        o.topics.camera_info = info_topic;
        o.topics.color = color_topic;
        py::gil_scoped_release free;
        return ros_io::import_bag_sequence(o).frames;
#else
        throw Error(bag, "this cropsight was built without ROS: bag files cannot be read (docs/ros.md)");
#endif
      },
      py::arg("bag"), py::arg("out"), py::arg("depth_topic"), py::arg("info_topic"), py::arg("color_topic"));
}

}  // namespace cropsight::python
