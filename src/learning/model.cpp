#include "cropsight/learning/model.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"

namespace cropsight::learning {

namespace {
constexpr const char* kFormat = "cropsight-model";
constexpr int kVersion = 1;

// The integer member `key` of `j` within [lo, hi], else Error. nlohmann's get<int>() casts a
// floating-point value such as 2e119 to int, which is undefined behaviour (fuzzing finding 24).
std::int64_t integer_at(const nlohmann::json& j, const char* key, std::int64_t lo, std::int64_t hi,
                        const std::string& where) {
  const nlohmann::json& v = j.at(key);
  const bool in_range = v.is_number_unsigned() ? v.get<std::uint64_t>() <= std::uint64_t(hi) &&
                                                     (lo <= 0 || v.get<std::uint64_t>() >= std::uint64_t(lo))
                        : v.is_number_integer() ? v.get<std::int64_t>() >= lo && v.get<std::int64_t>() <= hi
                                                : false;
  if (!in_range)
    throw Error(where, std::string("'") + key + "' must be an integer from " + std::to_string(lo) + " to " +
                           std::to_string(hi) + ", got " + v.dump());
  return v.get<std::int64_t>();
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + v[i];
  return s;
}
}  // namespace

float Model::score(std::span<const float> x, std::vector<float>& scratch) const {
  scratch.resize(x.size());
  standardizer.apply(x.data(), scratch.data());
  return classifier->score(scratch.data());
}

void Model::score_rows(std::span<const float> x, std::span<float> out, std::vector<float>& scratch) const {
  if (out.empty()) return;
  const std::size_t dim = x.size() / out.size();
  if (dim == 0 || dim * out.size() != x.size() || int(dim) != classifier->dim())
    throw std::invalid_argument("Model::score_rows: x must hold out.size() rows of the classifier's dimension");
  scratch.resize(x.size());
  for (std::size_t r = 0; r < out.size(); ++r) standardizer.apply(x.data() + r * dim, scratch.data() + r * dim);
  classifier->score_rows(scratch.data(), out.size(), out.data());
}

Model train_model(const Dataset& data, const ClassifierParams& params, ModelInfo info) {
  Model m;
  m.info = std::move(info);
  m.info.feature_dim = data.dim;
  m.params = params;
  m.standardizer = Standardizer::fit(data);
  m.classifier = train_classifier(m.standardizer.apply(data), params);
  return m;
}

void save_model(const std::filesystem::path& path, const Model& model) {
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["task"] = model.info.task;
  j["pipeline"] = model.info.pipeline;
  j["features"] = model.info.features;
  j["feature_dim"] = model.info.feature_dim;
  j["config"] = nlohmann::json::object();
  for (const auto& [k, v] : model.info.config) j["config"][k] = v;
  j["classifier"] = nlohmann::json::object();
  for (const auto& [k, v, doc] : dump_config(model.params)) j["classifier"][k] = v;
  j["classifier_model_size"] = model.classifier->model_size();
  j["standardizer"] = {{"mean", model.standardizer.mean}, {"std", model.standardizer.std}};
  j["provenance"] = model.info.provenance;
  j["payload"] = model.classifier->serialize();
  io::write_file_atomic(path, j.dump(1) + "\n");
}

Model load_model(const std::filesystem::path& path) {
  const std::string where = path.string();
  if (!std::filesystem::exists(path)) throw Error(where, "model file does not exist");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(io::read_file(path));
  } catch (const nlohmann::json::exception& e) {  // parse errors, and numbers out of range (1e999)
    throw Error(where, std::string("not a JSON model file (") + e.what() + ")");
  }
  try {
    if (!j.is_object() || j.value("format", "") != kFormat) throw Error(where, "not a cropsight model (format field)");
    if (integer_at(j, "version", 0, std::numeric_limits<int>::max(), where) != kVersion)
      throw Error(where, "model version " + j.at("version").dump() + " is not supported (expected 1)");
    Model m;
    m.info.task = j.at("task").get<std::string>();
    m.info.pipeline = j.at("pipeline").get<std::string>();
    m.info.features = j.at("features").get<std::vector<std::string>>();
    m.info.feature_dim = int(integer_at(j, "feature_dim", 1, std::numeric_limits<int>::max(), where));
    if (m.info.feature_dim <= 0) throw Error(where, "feature_dim must be positive");
    for (const auto& [k, v] : j.at("config").items()) m.info.config[k] = v.get<std::string>();
    if (j.contains("provenance")) m.info.provenance = j.at("provenance").get<std::map<std::string, std::string>>();
    ConfigMap cp;
    for (const auto& [k, v] : j.at("classifier").items()) cp[k] = v.get<std::string>();
    apply_config(m.params, cp, where + " classifier");
    m.standardizer.mean = j.at("standardizer").at("mean").get<std::vector<float>>();
    m.standardizer.std = j.at("standardizer").at("std").get<std::vector<float>>();
    if (m.standardizer.dim() != m.info.feature_dim || int(m.standardizer.std.size()) != m.info.feature_dim)
      throw Error(where, "standardizer size differs from feature_dim " + std::to_string(m.info.feature_dim));
    for (std::size_t i = 0; i < m.standardizer.mean.size(); ++i)
      if (!std::isfinite(m.standardizer.mean[i]) || !(m.standardizer.std[i] > 0.0f))
        throw Error(where, "standardizer has a non-finite mean or non-positive std");
    m.classifier = deserialize_classifier(m.params, m.info.feature_dim, j.at("payload").get<std::string>(), where);
    // The size recorded at save time: a payload edited or cut short is caught here if its own
    // parser let it through.
    if (j.contains("classifier_model_size") &&
        std::size_t(integer_at(j, "classifier_model_size", 0, std::numeric_limits<std::int64_t>::max(), where)) !=
            m.classifier->model_size())
      throw Error(where, "classifier payload holds " + std::to_string(m.classifier->model_size()) +
                             " entries but the file records classifier_model_size " +
                             j.at("classifier_model_size").dump() + " (damaged model file)");
    return m;
  } catch (const nlohmann::json::exception& e) {
    throw Error(where, std::string("malformed model file (") + e.what() + ")");
  }
}

void require_compatible(const ModelInfo& info, const std::string& task, const std::string& pipeline,
                        const std::vector<std::string>& features, int feature_dim, const std::string& where) {
  if (info.task != task) throw Error(where, "model was trained for task '" + info.task + "', not '" + task + "'");
  if (info.pipeline != pipeline)
    throw Error(where, "model was trained with pipeline '" + info.pipeline + "' but the detector runs '" + pipeline +
                           "' (retrain, or use --pipeline " + info.pipeline + ")");
  if (info.features != features)
    throw Error(where, "model was trained on features '" + join(info.features) + "' but the detector computes '" +
                           join(features) + "'");
  if (info.feature_dim != feature_dim)
    throw Error(where, "model expects " + std::to_string(info.feature_dim) + " feature values, the detector computes " +
                           std::to_string(feature_dim));
}

}  // namespace cropsight::learning
