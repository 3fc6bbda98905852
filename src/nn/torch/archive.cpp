// Archive I/O of the libtorch backend: TorchSegmenter's model files (weights plus the
// configuration as metadata) and the helpers declared in archive.hpp.
#include "nn/torch/archive.hpp"

#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/io/files.hpp"
#include "io/zip_check.hpp"
#include "nn/torch/segmenter_impl.hpp"

namespace cropsight::nn {

namespace torch_impl {

std::string torch_reason(const std::exception& e) {
  const auto* c = dynamic_cast<const c10::Error*>(&e);
  const std::string s = c ? c->what_without_backtrace() : e.what();
  return s.substr(0, s.find('\n'));
}

void save_archive_atomic(torch::serialize::OutputArchive& a, const std::filesystem::path& path) {
  io::write_atomic_with(path, [&](const std::filesystem::path& tmp) {
    try {
      a.save_to(tmp.string());
    } catch (const std::exception& e) {
      throw Error(path.string(), "cannot write: " + torch_reason(e));
    }
  });
}

void load_weights(torch::nn::Module& net, torch::serialize::InputArchive& a, const std::string& where) {
  std::vector<std::pair<std::string, std::vector<int64_t>>> shapes;
  for (const auto& p : net.named_parameters()) shapes.emplace_back(p.key(), p.value().sizes().vec());
  for (const auto& b : net.named_buffers()) shapes.emplace_back(b.key(), b.value().sizes().vec());
  try {
    net.load(a);
  } catch (const std::exception& e) {
    throw Error(where, "weights do not fit this network: " + torch_reason(e));
  }
  auto params = net.named_parameters();
  auto buffers = net.named_buffers();
  for (const auto& [key, shape] : shapes) {
    const torch::Tensor* t = params.find(key);
    if (!t) t = buffers.find(key);
    if (!t || t->sizes().vec() != shape)
      throw Error(where, "weights do not fit this network: '" + key +
                             "' has another shape (written with another arch, width or feature set?)");
  }
}

void open_model_archive(torch::serialize::InputArchive& a, const std::filesystem::path& path, const std::string& what) {
  const std::string where = path.string();
  if (!std::filesystem::exists(path)) throw Error(where, "no such model file");
  if (!std::filesystem::is_regular_file(path)) throw Error(where, "not a model file (a directory?)");
  io::detail::check_zip(io::read_file(path), where);  // libtorch trusts damaged archives (io/zip_check.hpp)
  try {
    a.load_from(where);
  } catch (const std::exception& e) {
    throw Error(where, "not a cropsight " + what + " model: " + torch_reason(e));
  }
}

void read_model_weights(torch::serialize::InputArchive& a, torch::nn::Module& net, const std::string& where) {
  torch::serialize::InputArchive m;
  try {
    a.read("model", m);
  } catch (const std::exception& e) {
    throw Error(where, "model file lacks its weights: " + torch_reason(e));
  }
  load_weights(net, m, where);
}

void write_checkpoint(const std::filesystem::path& path, const torch::nn::Module& net,
                      const torch::optim::Optimizer& opt, int epochs_done) {
  torch::serialize::OutputArchive a, m, o;
  net.save(m);
  opt.save(o);
  a.write("model", m);
  a.write("optim", o);
  a.write("epoch", torch::tensor(int64_t(epochs_done)));
  save_archive_atomic(a, path);
}

int read_checkpoint(const std::string& where, torch::nn::Module& net, torch::optim::Optimizer& opt) {
  if (!std::filesystem::is_regular_file(where)) throw Error(where, "not a checkpoint file (a directory?)");
  torch::serialize::InputArchive a, m, o;
  torch::Tensor e;
  io::detail::check_zip(io::read_file(where), where);  // libtorch trusts damaged archives
  try {
    a.load_from(where);
    a.read("model", m);
    a.read("optim", o);
    a.read("epoch", e);
  } catch (const std::exception& ex) {
    throw Error(where, "not a network checkpoint: " + torch_reason(ex));
  }
  load_weights(net, m, where);
  try {
    opt.load(o);
    return int(e.item<int64_t>());
  } catch (const std::exception& ex) {
    throw Error(where, "optimizer state does not fit this network: " + torch_reason(ex));
  }
}

}  // namespace torch_impl

namespace {
void put(torch::serialize::OutputArchive& a, const std::string& k, const std::string& v) { a.write(k, c10::IValue(v)); }
void put(torch::serialize::OutputArchive& a, const std::string& k, double v) { a.write(k, c10::IValue(v)); }
std::string get_s(torch::serialize::InputArchive& a, const std::string& k) {
  c10::IValue v;
  a.read(k, v);
  return v.toStringRef();
}
double get_d(torch::serialize::InputArchive& a, const std::string& k) {
  c10::IValue v;
  a.read(k, v);
  return v.toDouble();
}
}  // namespace

void TorchSegmenter::save(const std::filesystem::path& path) const {
  const auto& c = impl_->cfg;
  torch::serialize::OutputArchive a, m;
  impl_->net->save(m);
  a.write("model", m);
  put(a, "meta.kind", std::string("grape-pointnet"));
  put(a, "meta.arch", c.arch);
  put(a, "meta.features", c.features);
  put(a, "meta.num_classes", double(c.num_classes));
  put(a, "meta.num_points", double(c.num_points));
  put(a, "meta.sa1_points", double(c.sa1_points));
  put(a, "meta.sa2_points", double(c.sa2_points));
  put(a, "meta.sa3_points", double(c.sa3_points));
  put(a, "meta.k1", double(c.k1));
  put(a, "meta.k2", double(c.k2));
  put(a, "meta.k3", double(c.k3));
  put(a, "meta.width", double(c.width));
  put(a, "meta.seed", double(c.seed));
  put(a, "meta.batch_size", double(c.batch_size));
  torch_impl::save_archive_atomic(a, path);
}

std::unique_ptr<detail::SegmenterBackend> TorchSegmenter::load(const std::filesystem::path& path, int threads) {
  const std::string where = path.string();
  check_thread_count(threads, "threads");
  torch::serialize::InputArchive a;
  torch_impl::open_model_archive(a, path, "network");
  PointNetConfig c;
  try {
    if (get_s(a, "meta.kind") != "grape-pointnet") throw Error(where, "not a grape network model");
    c.arch = get_s(a, "meta.arch");
    c.features = get_s(a, "meta.features");
    c.num_classes = int(get_d(a, "meta.num_classes"));
    c.num_points = int(get_d(a, "meta.num_points"));
    c.sa1_points = int(get_d(a, "meta.sa1_points"));
    c.sa2_points = int(get_d(a, "meta.sa2_points"));
    c.sa3_points = int(get_d(a, "meta.sa3_points"));
    c.k1 = int(get_d(a, "meta.k1"));
    c.k2 = int(get_d(a, "meta.k2"));
    c.k3 = int(get_d(a, "meta.k3"));
    c.width = int(get_d(a, "meta.width"));
    c.seed = std::uint64_t(get_d(a, "meta.seed"));
    c.batch_size = int(get_d(a, "meta.batch_size"));
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    throw Error(where, "model file lacks its metadata");
  }
  c.threads = threads;
  c.validate(where + ": metadata");
  auto s = std::make_unique<TorchSegmenter>(c);
  torch_impl::read_model_weights(a, *s->impl_->net, where);
  return s;
}

}  // namespace cropsight::nn
