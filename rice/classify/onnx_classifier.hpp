#pragma once
// A network a user trained elsewhere, given as ONNX and run through OpenCV's dnn module (docs/rice.md,
// "A network of your own (ONNX)"). On disk it is a pair of files:
//   NET.onnx   the network: one input N x C x H x W (NCHW, float), one output of one score per class;
//   NET.json   beside it (same name, .json), what riceasv needs to feed it:
//     {"format": "riceasv onnx classifier", "version": 1,
//      "classes": ["low", "medium", "high"],          output k is the score of classes[k]
//      "input": {"width": 64, "height": 64, "channels": 1, "colour_order": "rgb"},
//      "crop_mm": 12,                                  side of the square cut around each grain, mm
//      "normalisation": {"mean": [0], "std": [1]},     per channel: (pixel / 255 - mean) / std
//      "output": "probabilities"}                      or "logits" (riceasv applies the softmax)
// `--onnx DIR` means DIR/net.onnx and DIR/net.json.
// The crop rule: a square of n = round(crop_mm / pixel size) photograph pixels centred on the grain's
// centroid (results.csv's x_px, y_px; top-left pixel round(x - n/2), round(y - n/2)), parts outside
// the photograph filled with the dish's grey level, resized to width x height as 8-bit pixels with
// cv::INTER_AREA, then normalised. channels 1: the grey image riceasv measures; 3: the photograph's
// colour in colour_order ("rgb" as torchvision and Keras load images, or "bgr").
// Not collective.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <string>
#include <vector>

namespace suite::rice {

struct OnnxSpec {
  std::vector<std::string> classes;
  int width = 0, height = 0, channels = 1;
  bool rgb = true;  // channels 3: RGB order (else BGR)
  double crop_mm = 0;
  std::vector<double> mean, std;  // one per channel
  bool logits = false;            // the output needs a softmax
};

// NET.onnx and its NET.json for an --onnx argument (a folder: net.onnx and net.json in it).
struct OnnxFiles {
  std::filesystem::path onnx, json;
};
OnnxFiles onnx_files(const std::filesystem::path& argument);

// The JSON's contents; InputError naming the file, the key and what is valid.
OnnxSpec parse_onnx_spec(const nlohmann::json& j, const std::filesystem::path& file);

// The network's input for a grain centred at (x, y) pixels of `image` (CV_8UC1, or CV_8UC3 in BGR as
// OpenCV reads it) by the crop rule above, before normalisation: CV_8UC1, or CV_8UC3 in the network's
// colour order, of spec.width x spec.height. `fill` is the dish's grey level for the parts outside the
// photograph. `region`, when given, receives the crop's square in photograph pixels.
cv::Mat crop_for_network(const OnnxSpec& spec, const cv::Mat& image, double x, double y, double mm_per_px, double fill,
                         cv::Rect* region = nullptr);

class OnnxClassifier {
 public:
  // Reads NET.json and NET.onnx and runs the network once on a blank input, so that a file that is
  // not ONNX, an input size the network does not take, or an output that is not one score per class
  // stops here with one line naming the file and the fix.
  static OnnxClassifier load(const std::filesystem::path& argument);

  // crop_for_network() with this network's spec.
  cv::Mat crop(const cv::Mat& image, double x, double y, double mm_per_px, double fill,
               cv::Rect* region = nullptr) const {
    return crop_for_network(spec_, image, x, y, mm_per_px, fill, region);
  }

  // The class scores of one crop (as crop() returns it): probabilities, softmax applied to logits.
  std::vector<double> scores(const cv::Mat& crop) const;

  const OnnxSpec& spec() const { return spec_; }
  const OnnxFiles& files() const { return files_; }

 private:
  OnnxSpec spec_;
  OnnxFiles files_;
  mutable cv::dnn::Net net_;  // forward() is not const
};

}  // namespace suite::rice
