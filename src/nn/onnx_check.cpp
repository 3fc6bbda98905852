#include "nn/onnx_check.hpp"

#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

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

// The most elements a tensor the model asks for may have: 2^28 (1 GiB of floats), far above any
// detector's (a 640x640 YOLO's largest is about 1.6e6). A Reshape to 1x3x4096x67108865 made
// OpenCV 4.6 allocate 3.3 TB (fuzz_onnx_model; fuzz/regressions/onnx_model/).
constexpr long long kMaxElements = 1ll << 28;

// The int64 values of a shape-like constant (raw_data or int64_data); empty when of another type.
std::vector<long long> int64_values(const onnx::TensorProto& t) {
  std::vector<long long> v;
  if (t.data_type() != onnx::TensorProto::INT64) return v;
  if (t.has_raw_data() && !t.raw_data().empty()) {
    for (std::size_t i = 0; i + 8 <= t.raw_data().size(); i += 8) {
      long long x = 0;
      for (int b = 0; b < 8; ++b) x |= (long long)(unsigned char)t.raw_data()[i + std::size_t(b)] << (8 * b);
      v.push_back(x);
    }
  } else {
    v.assign(t.int64_data().begin(), t.int64_data().end());
  }
  return v;
}

// A shape the model gives as a constant: -1 (inferred) and 0 (copied) count as 1 here, the
// input's own size being checked where it enters.
void check_shape(const std::vector<long long>& dims, const std::string& what, const std::string& where) {
  long long elements = 1;
  for (const long long d : dims) {
    if (d < -1) throw Error(where, what + " has a negative dimension");
    const long long f = d > 0 ? d : 1;
    if (f > kMaxElements || elements > kMaxElements / f)
      throw Error(where, what + " asks for a tensor of more than " + std::to_string(kMaxElements) + " elements");
    elements *= f;
  }
}

// Every value a node reads must be defined: by the graph's inputs or initializers, by a node of
// the graph, or (in a subgraph) by the scope around it. OpenCV 4.6 looks a Conv's weights up by
// name and dereferences what it finds: a name nothing defines made it read address 0
// (fuzz_onnx_model; fuzz/regressions/onnx_model/).
void check_names(const onnx::GraphProto& g, const std::set<std::string>& defined, const std::string& where) {
  for (const auto& n : g.node())
    for (const auto& name : n.input())
      if (!name.empty() && !defined.count(name))
        throw Error(where, n.op_type() + " node '" + (n.name().empty() && n.output_size() ? n.output(0) : n.name()) +
                               "' reads '" + name + "', which nothing in the model defines");
}

void check_graph(const onnx::GraphProto& g, const std::string& where, int depth, std::set<std::string> defined) {
  if (depth > 16) throw Error(where, "subgraphs nested too deep");
  for (const auto& in : g.input()) defined.insert(in.name());
  for (const auto& t : g.initializer()) defined.insert(t.name());
  for (const auto& n : g.node())
    for (const auto& out : n.output()) defined.insert(out);
  check_names(g, defined, where);
  for (const auto& t : g.initializer()) check_tensor(t, where);
  for (const auto& in : g.input()) {
    if (!in.type().has_tensor_type() || !in.type().tensor_type().has_shape()) continue;
    std::vector<long long> dims;
    for (const auto& d : in.type().tensor_type().shape().dim()) dims.push_back(d.has_dim_value() ? d.dim_value() : 1);
    check_shape(dims, "input '" + in.name() + "'", where);
  }
  // Constants by name (initializers and Constant nodes' values), for the shape inputs below.
  std::map<std::string, const onnx::TensorProto*> constants;
  for (const auto& t : g.initializer()) constants[t.name()] = &t;
  for (const auto& n : g.node())
    if (n.op_type() == "Constant" && n.output_size() == 1)
      for (const auto& a : n.attribute())
        if (a.name() == "value" && a.has_t()) constants[n.output(0)] = &a.t();
  for (const auto& n : g.node()) {
    // Operators whose output shape is a constant input: Reshape / Expand (input 1), ConstantOfShape (0).
    int shape_input = -1;
    if (n.op_type() == "Reshape" || n.op_type() == "Expand") shape_input = 1;
    if (n.op_type() == "ConstantOfShape") shape_input = 0;
    if (shape_input >= 0 && n.input_size() > shape_input) {
      const auto c = constants.find(n.input(shape_input));
      if (c != constants.end())
        check_shape(int64_values(*c->second),
                    n.op_type() + " node '" + (n.name().empty() && n.output_size() ? n.output(0) : n.name()) + "'",
                    where);
    }
    for (const auto& a : n.attribute()) {
      if (a.has_t()) check_tensor(a.t(), where);
      for (const auto& t : a.tensors()) check_tensor(t, where);
      if (a.has_g()) check_graph(a.g(), where, depth + 1, defined);
      for (const auto& sub : a.graphs()) check_graph(sub, where, depth + 1, defined);
    }
  }
}

}  // namespace

void check_onnx_tensors(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "no such ONNX file");
  onnx::ModelProto model;
  if (!model.ParseFromIstream(&in)) throw Error(path.string(), "not an ONNX model");
  check_graph(model.graph(), path.string(), 0, {});
}
#else
void check_onnx_tensors(const std::filesystem::path&) {}
#endif

}  // namespace cropsight::nn
