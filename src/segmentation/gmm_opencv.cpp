// cv::ml::EM on the same points and settings as fit_gmm(): the reference implementation that
// tests (log-likelihood agreement) and benchmarks (speed) compare our EM against.
#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/segmentation/gmm.hpp"

namespace cropsight::segmentation {

GmmResult fit_gmm_opencv(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg, const GmmModel* init,
                         const std::string& where) {
  if (cfg.components < 1) throw Error(where, "components must be >= 1");
  if (int(points.size()) < cfg.components) throw Error(where, "fewer points than components");
  const int n = int(points.size()), k = cfg.components;
  cv::Mat samples(n, 3, CV_64F);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) samples.at<double>(i, d) = points[i][d];

  auto em = cv::ml::EM::create();
  em->setClustersNumber(k);
  em->setCovarianceMatrixType(cv::ml::EM::COV_MAT_GENERIC);
  em->setTermCriteria(
      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, cfg.max_iterations, cfg.tolerance));
  cv::Mat log_likelihoods, labels;
  bool ok = false;
  if (init) {
    if (init->size() != k) throw Error(where, "initial model has a different number of components");
    cv::Mat means(k, 3, CV_64F), weights(1, k, CV_64F);
    std::vector<cv::Mat> covs;
    for (int j = 0; j < k; ++j) {
      weights.at<double>(0, j) = init->weights[j];
      cv::Mat c(3, 3, CV_64F);
      for (int r = 0; r < 3; ++r) {
        means.at<double>(j, r) = init->means[j][r];
        for (int s = 0; s < 3; ++s) c.at<double>(r, s) = init->covariances[j](r, s);
      }
      covs.push_back(c);
    }
    ok = em->trainE(samples, means, covs, weights, log_likelihoods, labels);
  } else {
    ok = em->trainEM(samples, log_likelihoods, labels);
  }
  if (!ok) throw Error(where, "cv::ml::EM failed to train");

  GmmResult r;
  const cv::Mat means = em->getMeans(), weights = em->getWeights();
  std::vector<cv::Mat> covs;
  em->getCovs(covs);
  for (int j = 0; j < k; ++j) {
    r.model.weights.push_back(weights.at<double>(0, j));
    r.model.means.emplace_back(means.at<double>(j, 0), means.at<double>(j, 1), means.at<double>(j, 2));
    Eigen::Matrix3d c;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) c(a, b) = covs[j].at<double>(a, b);
    r.model.covariances.push_back(c);
  }
  r.labels.resize(n);
  double total = 0;
  for (int i = 0; i < n; ++i) {
    r.labels[i] = labels.at<int>(i, 0);
    total += log_likelihoods.at<double>(i, 0);
  }
  r.log_likelihood = total / double(n);
  r.iterations = -1;  // cv::ml::EM does not report it
  r.converged = true;
  return r;
}

}  // namespace cropsight::segmentation
