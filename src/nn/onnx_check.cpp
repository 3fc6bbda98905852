#include "nn/onnx_check.hpp"

#include <fstream>
#include <string>

#include "cropsight/core/error.hpp"

#ifdef CROPSIGHT_HAVE_ONNX
#include <onnx/onnx_pb.h>
#endif

namespace cropsight::nn {

#ifdef CROPSIGHT_HAVE_ONNX
namespace {

// Bytes per element of an ONNX TensorProto data type; 0 for those OpenCV does not take.
int element_bytes(int type) {
  switch (type) {
    case onnx::TensorProto::UINT8:
    case onnx::TensorProto::INT8:
    case onnx::TensorProto::BOOL:
      return 1;
    case onnx::TensorProto::UINT16:
    case onnx::TensorProto::INT16:
    case onnx::TensorProto::FLOAT16:
      return 2;
    case onnx::TensorProto::FLOAT:
    case onnx::TensorProto::INT32:
    case onnx::TensorProto::UINT32:
      return 4;
    case onnx::TensorProto::INT64:
    case onnx::TensorProto::DOUBLE:
    case onnx::TensorProto::UINT64:
      return 8;
    default:
      return 0;
  }
}

// The values a tensor stores in its typed fields (raw_data empty).
long long typed_count(const onnx::TensorProto& t) {
  return (long long)t.float_data_size() + t.int32_data_size() + t.int64_data_size() + t.double_data_size() +
         t.uint64_data_size();
}

void check_tensor(const onnx::TensorProto& t, const std::string& where) {
  const std::string name = "tensor '" + t.name() + "'";
  if (t.data_location() == onnx::TensorProto::EXTERNAL)
    throw Error(where, name + " keeps its data in an external file (not supported)");
  const int bytes = element_bytes(t.data_type());
  if (bytes == 0) throw Error(where, name + " has an unsupported data type (" + std::to_string(t.data_type()) + ")");
  long long elements = 1;
  for (const auto d : t.dims()) {
    if (d < 0 || d > (1ll << 31) || (d > 0 && elements > (1ll << 31) / d))
      throw Error(where, name + " has an impossible shape");
    elements *= d;
  }
  const long long have =
      t.has_raw_data() && !t.raw_data().empty() ? (long long)t.raw_data().size() / bytes : typed_count(t);
  const bool raw_whole = !t.has_raw_data() || t.raw_data().size() % std::size_t(bytes) == 0;
  if (have != elements || !raw_whole)
    throw Error(where, name + " holds " + std::to_string(have) + " values but its shape has " +
                           std::to_string(elements) + " (a truncated or damaged file?)");
}

void check_graph(const onnx::GraphProto& g, const std::string& where, int depth) {
  if (depth > 16) throw Error(where, "subgraphs nested too deep");
  for (const auto& t : g.initializer()) check_tensor(t, where);
  for (const auto& n : g.node()) {
    for (const auto& a : n.attribute()) {
      if (a.has_t()) check_tensor(a.t(), where);
      for (const auto& t : a.tensors()) check_tensor(t, where);
      if (a.has_g()) check_graph(a.g(), where, depth + 1);
      for (const auto& sub : a.graphs()) check_graph(sub, where, depth + 1);
    }
  }
}

}  // namespace

void check_onnx_tensors(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "no such ONNX file");
  onnx::ModelProto model;
  if (!model.ParseFromIstream(&in)) throw Error(path.string(), "not an ONNX model");
  check_graph(model.graph(), path.string(), 0);
}
#else
void check_onnx_tensors(const std::filesystem::path&) {}
#endif

}  // namespace cropsight::nn
