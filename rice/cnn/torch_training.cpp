#include "rice/cnn/torch_training.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <thread>

namespace suite::rice::cnn {
namespace {

// One of the eight turns and mirror images of each crop in `batch` (N x C x H x W), drawn from `rng`;
// non-square crops only the turn by 180 degrees and the mirror images.
torch::Tensor turned(const torch::Tensor& batch, std::mt19937_64& rng) {
  const bool square = batch.size(2) == batch.size(3);
  std::vector<torch::Tensor> out;
  out.reserve(static_cast<std::size_t>(batch.size(0)));
  for (int64_t i = 0; i < batch.size(0); ++i) {
    auto k = static_cast<int64_t>(rng() % 8);
    if (!square) k -= k % 2;  // 0, 2, 4, 6: no quarter turns
    torch::Tensor x = torch::rot90(batch[i], k % 4, {1, 2});
    if (k >= 4) x = torch::flip(x, {2});
    out.push_back(x);
  }
  return torch::stack(out);
}

}  // namespace

void use_threads(int threads) {
  const int n = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (torch::get_num_threads() != n) torch::set_num_threads(n);
}

torch::Tensor to_tensor(const cv::Mat& crops, int width, int height, int channels, const std::vector<double>& mean,
                        const std::vector<double>& std) {
  if (crops.rows > 0 && (crops.type() != CV_8UC1 || crops.cols != width * height * channels || !crops.isContinuous()))
    throw std::logic_error(
        fmt::format("crops must be continuous CV_8UC1 rows of {} x {} x {} pixels", height, width, channels));
  if (crops.rows == 0) return torch::zeros({0, channels, height, width});
  // Each channel as OpenCV's convertTo scales it (the same floats for one channel as for many).
  std::vector<cv::Mat> planes;
  cv::split(crops.reshape(channels, crops.rows), planes);
  for (int c = 0; c < channels; ++c) {
    const auto k = static_cast<std::size_t>(c);
    planes[k].convertTo(planes[k], CV_32F, 1.0 / (255.0 * std[k]), -mean[k] / std[k]);
  }
  cv::Mat scaled;
  cv::merge(planes, scaled);
  return torch::from_blob(scaled.data, {crops.rows, height, width, channels}, torch::kFloat32)
      .permute({0, 3, 1, 2})
      .clone(torch::MemoryFormat::Contiguous);  // a copy: `scaled` goes with this scope
}

void train_epochs(const std::function<torch::Tensor(const torch::Tensor&)>& forward,
                  const std::vector<torch::Tensor>& parameters, const std::function<void(bool)>& training,
                  const torch::Tensor& x, const std::vector<int>& labels, const CnnOptions& options,
                  const std::function<void(int)>& after_epoch) {
  const torch::Tensor y = torch::tensor(std::vector<int64_t>(labels.begin(), labels.end()), torch::kInt64);
  torch::optim::Adam optimiser(parameters,
                               torch::optim::AdamOptions(options.learning_rate).weight_decay(options.weight_decay));
  std::mt19937_64 rng(options.seed);
  std::vector<int64_t> order(static_cast<std::size_t>(x.size(0)));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int64_t>(i);
  for (int epoch = 1; epoch <= options.epochs; ++epoch) {
    training(true);
    for (std::size_t i = order.size(); i > 1; --i)  // Fisher-Yates, the same with every standard library
      std::swap(order[i - 1], order[static_cast<std::size_t>(rng() % i)]);
    for (std::size_t start = 0; start < order.size(); start += static_cast<std::size_t>(options.batch)) {
      const std::size_t end = std::min(order.size(), start + static_cast<std::size_t>(options.batch));
      if (end - start < 2 && start > 0) break;  // batch normalisation needs two crops; one left over sits out
      const torch::Tensor index = torch::tensor(std::vector<int64_t>(order.begin() + static_cast<std::ptrdiff_t>(start),
                                                                     order.begin() + static_cast<std::ptrdiff_t>(end)),
                                                torch::kInt64);
      torch::Tensor batch = x.index_select(0, index);
      if (options.augment) batch = turned(batch, rng);
      optimiser.zero_grad();
      const torch::Tensor loss = torch::nn::functional::cross_entropy(forward(batch), y.index_select(0, index));
      loss.backward();
      optimiser.step();
    }
    if (after_epoch) after_epoch(epoch);
  }
  training(false);
}

cv::Mat probabilities_of(const torch::Tensor& logits) {
  const torch::Tensor p = torch::softmax(logits.to(torch::kFloat64), 1).contiguous();
  cv::Mat out(static_cast<int>(p.size(0)), static_cast<int>(p.size(1)), CV_64F);
  std::copy(p.data_ptr<double>(), p.data_ptr<double>() + p.numel(), out.ptr<double>());
  return out;
}

}  // namespace suite::rice::cnn
