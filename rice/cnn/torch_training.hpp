#pragma once
// What the suite's network (grain_cnn.hpp) and a lab's pretrained TorchScript network
// (pretrained_net.hpp) share when trained or run with libtorch: crops as tensors, the training loop
// and the probabilities. Internal to rice/cnn/ (it includes libtorch). Not collective.
#include <torch/torch.h>

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "rice/cnn/grain_cnn.hpp"

namespace suite::rice::cnn {

// libtorch's thread count for this process: `threads`, or every core for 0.
void use_threads(int threads);

// Rows of CV_8U crops (each height x width x channels, channels interleaved as crop_for_network
// writes them) as an N x channels x height x width float tensor of (pixel / 255 - mean) / std per
// channel.
torch::Tensor to_tensor(const cv::Mat& crops, int width, int height, int channels, const std::vector<double>& mean,
                        const std::vector<double>& std);

// `options.epochs` passes of Adam (options.learning_rate, weight_decay) on the cross-entropy of
// `forward` over `x` and each row's class index in `labels`, in mini-batches of options.batch in an order seeded
// with options.seed, each crop turned by a random one of the eight turns and mirror images (non-square
// crops: the four that keep the shape) when options.augment. `training(true)` is called before each
// pass, `after_epoch(pass)` after it (when given); a lone last crop sits its pass out (batch
// normalisation needs two).
void train_epochs(const std::function<torch::Tensor(const torch::Tensor&)>& forward,
                  const std::vector<torch::Tensor>& parameters, const std::function<void(bool)>& training,
                  const torch::Tensor& x, const std::vector<int>& labels, const CnnOptions& options,
                  const std::function<void(int)>& after_epoch);

// Softmax of the logits, one row per crop (CV_64F), in double precision.
cv::Mat probabilities_of(const torch::Tensor& logits);

}  // namespace suite::rice::cnn
