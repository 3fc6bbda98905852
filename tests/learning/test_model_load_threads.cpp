// Models loaded from several threads at once (Dask workers, one pipeline per thread): libsvm
// parses with strtok and switches the locale, so unserialised loads crashed; the classifier
// serialises them. Every thread must get the same model as a load on its own.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "cropsight/learning/model.hpp"
#include "testing/testing.hpp"

namespace model_load_threads_test {
using namespace cropsight;

TEST(ModelLoadThreads, SvmModelsLoadInParallelThreads) {
  const auto path = cropsight::testing::source_dir() / "models" / "broccoli-oes-uk.json";
  const learning::Model alone = learning::load_model(path);
  std::vector<std::size_t> sizes(4, 0);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < sizes.size(); ++t)
    threads.emplace_back([&, t] {
      for (int k = 0; k < 3; ++k) sizes[t] = learning::load_model(path).classifier->model_size();
    });
  for (auto& th : threads) th.join();
  for (std::size_t s : sizes) EXPECT_EQ(s, alone.classifier->model_size());
}

}  // namespace model_load_threads_test
