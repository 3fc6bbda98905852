// nn::CenterNet's ONNX graph, built with libonnx-dev's protobuf classes (center_onnx_writer.hpp).
// Without libonnx-dev (CROPSIGHT_HAVE_ONNX unset) export throws and reading falls back to
// OpenCV's own check of the file.
#include "nn/center_onnx_writer.hpp"

#include <fstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"

#ifdef CROPSIGHT_HAVE_ONNX
#include <onnx/onnx_pb.h>
#endif

namespace cropsight::nn {

#ifdef CROPSIGHT_HAVE_ONNX
namespace {

class GraphBuilder {
 public:
  explicit GraphBuilder(onnx::GraphProto* g) : g_(g) {}

  void initializer(const std::string& name, const std::vector<float>& data, const std::vector<std::int64_t>& dims) {
    auto* t = g_->add_initializer();
    t->set_name(name);
    t->set_data_type(onnx::TensorProto::FLOAT);
    for (auto d : dims) t->add_dims(d);
    t->mutable_raw_data()->assign(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(float));
  }

  onnx::NodeProto* node(const std::string& op, const std::vector<std::string>& in, const std::string& out) {
    auto* n = g_->add_node();
    n->set_op_type(op);
    n->set_name(out);
    for (const auto& i : in) n->add_input(i);
    n->add_output(out);
    return n;
  }

  static void ints(onnx::NodeProto* n, const std::string& name, const std::vector<std::int64_t>& v) {
    auto* a = n->add_attribute();
    a->set_name(name);
    a->set_type(onnx::AttributeProto::INTS);
    for (auto x : v) a->add_ints(x);
  }
  static void text(onnx::NodeProto* n, const std::string& name, const std::string& v) {
    auto* a = n->add_attribute();
    a->set_name(name);
    a->set_type(onnx::AttributeProto::STRING);
    a->set_s(v);
  }

  // A folded convolution, then ReLU when it has one: the name of its output.
  std::string conv(const detail::FoldedConv& c, const std::string& input) {
    initializer(c.name + ".weight", c.weight, {c.out, c.in, c.kernel, c.kernel});
    initializer(c.name + ".bias", c.bias, {c.out});
    const std::string out = c.name + (c.relu ? ".conv" : "");
    auto* n = node("Conv", {input, c.name + ".weight", c.name + ".bias"}, out);
    const std::int64_t p = c.kernel / 2;
    ints(n, "kernel_shape", {c.kernel, c.kernel});
    ints(n, "strides", {c.stride, c.stride});
    ints(n, "pads", {p, p, p, p});
    if (!c.relu) return out;
    node("Relu", {out}, c.name);
    return c.name;
  }

  // Nearest upsampling by 2 (torch's nearest: source index floor(i / 2)).
  std::string up(const std::string& input) {
    auto* n = node("Resize", {input, "", "up.scales"}, input + ".up");
    text(n, "mode", "nearest");
    text(n, "coordinate_transformation_mode", "asymmetric");
    text(n, "nearest_mode", "floor");
    return input + ".up";
  }

  void value(onnx::ValueInfoProto* v, const std::string& name, const std::vector<std::int64_t>& dims) {
    v->set_name(name);
    auto* t = v->mutable_type()->mutable_tensor_type();
    t->set_elem_type(onnx::TensorProto::FLOAT);
    for (auto d : dims) t->mutable_shape()->add_dim()->set_dim_value(d);
  }

 private:
  onnx::GraphProto* g_;
};

}  // namespace

void write_center_onnx(const CenterNetConfig& cfg, const std::vector<detail::FoldedConv>& convs,
                       const std::filesystem::path& path) {
  std::map<std::string, const detail::FoldedConv*> by_name;
  for (const auto& c : convs) by_name[c.name] = &c;
  auto at = [&](const std::string& n) -> const detail::FoldedConv& {
    const auto it = by_name.find(n);
    if (it == by_name.end()) throw Error(path.string(), "the network has no layer '" + n + "' (a build mix-up)");
    return *it->second;
  };
  onnx::ModelProto model;
  model.set_ir_version(7);
  model.set_producer_name("cropsight");
  model.add_opset_import()->set_version(11);
  for (const auto& [key, value, doc] : dump_config(cfg)) {
    auto* m = model.add_metadata_props();
    m->set_key("cropsight." + key);
    m->set_value(value);
  }
  auto* kind = model.add_metadata_props();
  kind->set_key("cropsight.kind");
  kind->set_value("cropsight-centernet");
  auto* g = model.mutable_graph();
  g->set_name("centernet");
  GraphBuilder b(g);
  const std::int64_t C = cfg.num_classes(), H = cfg.input_height, W = cfg.input_width;
  b.value(g->add_input(), "images", {1, 3, H, W});
  b.initializer("up.scales", {1.f, 1.f, 2.f, 2.f}, {4});
  // Backbone, FPN-lite and heads, as NetImpl::forward.
  std::string x = "images";
  std::vector<std::string> c;
  for (int s = 0; s < 5; ++s) {
    x = b.conv(at("s" + std::to_string(s) + "a"), x);
    x = b.conv(at("s" + std::to_string(s) + "b"), x);
    c.push_back(x);
  }
  std::string p = b.conv(at("lat5"), c[4]);
  for (int level : {4, 3, 2}) {
    const std::string lat = b.conv(at("lat" + std::to_string(level)), c[std::size_t(level - 1)]);
    const std::string sum = "sum" + std::to_string(level);
    b.node("Add", {b.up(p), lat}, sum);
    p = b.conv(at("smooth" + std::to_string(level)), sum);
  }
  const struct {
    const char *head, *output;
    bool sigmoid;
    std::int64_t channels;
  } heads[] = {
      {"hm", "heatmap", true, C}, {"wh", "size", false, 2}, {"off", "offset", false, 2}, {"seg", "mask", true, C}};
  for (const auto& h : heads) {
    const std::string hidden = b.conv(at(std::string(h.head) + ".hidden"), p);
    detail::FoldedConv out = at(std::string(h.head) + ".out");
    if (h.sigmoid) {
      out.name = std::string(h.head) + ".logits";
      b.node("Sigmoid", {b.conv(out, hidden)}, h.output);
    } else {
      out.name = h.output;
      b.conv(out, hidden);
    }
    b.value(g->add_output(), h.output, {1, h.channels, H / 4, W / 4});
  }
  std::string bytes;
  if (!model.SerializeToString(&bytes)) throw Error(path.string(), "cannot serialise the ONNX model");
  io::write_atomic_with(path, [&](const std::filesystem::path& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    f.write(bytes.data(), std::streamsize(bytes.size()));
    if (!f) throw Error(path.string(), "cannot write");
  });
}

OnnxModelInfo read_onnx_info(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "no such ONNX file");
  onnx::ModelProto model;
  if (!model.ParseFromIstream(&in)) throw Error(path.string(), "not an ONNX model");
  OnnxModelInfo info;
  for (const auto& m : model.metadata_props())
    if (m.key().rfind("cropsight.", 0) == 0) info.metadata[m.key().substr(10)] = m.value();
  for (const auto& o : model.graph().output()) info.outputs.push_back(o.name());
  return info;
}

#else

void write_center_onnx(const CenterNetConfig&, const std::vector<detail::FoldedConv>&,
                       const std::filesystem::path& path) {
  throw Error(path.string(), "cropsight was built without libonnx-dev: no ONNX export (scripts/install-deps.sh)");
}
OnnxModelInfo read_onnx_info(const std::filesystem::path& path) {
  throw Error(path.string(), "cropsight was built without libonnx-dev: cannot read the detector's metadata");
}

#endif

}  // namespace cropsight::nn
