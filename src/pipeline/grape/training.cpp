#include "cropsight/pipeline/grape/training.hpp"

#include <unistd.h>

#include <cstdarg>
#include <cstdio>

#include "cropsight/core/timer.hpp"
#include "cropsight/pipeline/grape/model.hpp"

namespace cropsight::pipeline::grape {

namespace {
namespace fs = std::filesystem;

// Removes a fold's temporary model however its fold ends (an exception included).
struct RemoveOnExit {
  fs::path path;
  ~RemoveOnExit() {
    std::error_code ec;
    if (!path.empty()) fs::remove(path, ec);
  }
};

// printf into a string (the progress lines' fixed number formats).
__attribute__((format(printf, 1, 2))) std::string formatted(const char* fmt, ...) {
  std::va_list args, copy;
  va_start(args, fmt);
  va_copy(copy, args);
  std::string s(std::size_t(std::vsnprintf(nullptr, 0, fmt, copy)), '\0');
  va_end(copy);
  std::vsnprintf(s.data(), s.size() + 1, fmt, args);
  va_end(args);
  return s;
}

void train_network(const nn::PointNetConfig& cfg, const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                   const fs::path& out, const TrainLog& log) {
  nn::PointSegmenter net(cfg);
  if (log)
    log(formatted("%s, features %s, %zu parameters, %zu training clouds, %d thread%s", cfg.arch.c_str(),
                  cfg.features.c_str(), net.parameter_count(), train.size(), cfg.threads, cfg.threads == 1 ? "" : "s"));
  net.train(train, val, [&](const nn::EpochLog& l) {
    if (!log) return;
    if (l.val_miou >= 0)
      log(formatted("epoch %d/%d  loss %.4f  train acc %.4f  val mIoU %.4f  lr %.2e  %.1f s", l.epoch, cfg.epochs,
                    l.loss, l.train_acc, l.val_miou, l.lr, l.seconds));
    else
      log(formatted("epoch %d/%d  loss %.4f  train acc %.4f  lr %.2e  %.1f s", l.epoch, cfg.epochs, l.loss, l.train_acc,
                    l.lr, l.seconds));
  });
  net.save(out);
}

}  // namespace

void train_grape_model(const TrainConfig& cfg, const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                       const std::filesystem::path& out, const TrainLog& log) {
  if (cfg.model != "gbdt") return train_network(cfg.net, train, val, out, log);
  train_grape_gbdt(train, cfg.gbdt, log).save(out);
}

CrossValidation cross_validate_grape(const TrainConfig& cfg, const std::vector<Cloud>& clouds, const FoldPlan& plan,
                                     const TrainLog& log) {
  CrossValidation cv;
  const std::vector<int> fold = grape_folds(clouds.size(), plan.folds, plan.split_seed);
  for (int k = plan.first; k < plan.last; ++k) {
    std::vector<Cloud> tr, va;
    for (std::size_t i = 0; i < clouds.size(); ++i) (fold[i] == k ? va : tr).push_back(clouds[i]);
    const std::string tag = "[fold " + std::to_string(k + 1) + "/" + std::to_string(plan.folds) + "] ";
    const fs::path model_path =
        !plan.keep_model.empty()
            ? plan.keep_model
            : fs::temp_directory_path() / ("cropsight-grape-fold-" + std::to_string(::getpid()) + "-" +
                                           std::to_string(k) + (cfg.model == "gbdt" ? ".json" : ".pt"));
    const RemoveOnExit fold_model{plan.keep_model.empty() ? model_path : fs::path()};
    const Stopwatch clock;
    train_grape_model(cfg, tr, va, model_path, [&](const std::string& line) {
      if (log) log(tag + line);
    });
    cv.train_seconds += clock.seconds();
    const auto ev = evaluate_grape(Model::load(model_path, plan.eval_threads), va);
    if (log)
      log(tag + formatted("held-out: OAcc %.4f  mAcc %.4f  mIoU %.4f  (%zu clouds, %.1f ms/cloud, train %.0f s)",
                          ev.confusion.overall_accuracy(), ev.confusion.mean_accuracy(), ev.confusion.mean_iou(),
                          ev.clouds, ev.ms_per_cloud(), clock.seconds()));
    cv.pooled.merge(ev);
  }
  return cv;
}

}  // namespace cropsight::pipeline::grape
