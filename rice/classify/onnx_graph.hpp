#pragma once
// An ONNX file made importable by OpenCV 4.6's dnn module where an exporter's habit trips its importer
// (docs/rice.md, "A network of your own (ONNX)"). PyTorch (1.13) shares equal weights between layers
// through Identity nodes: every zero bias of a ResNet-18's convolutions, once the batch normalisations
// are folded into them, is one initializer read through sixteen Identity nodes, and OpenCV 4.6 fails
// on an Identity whose input is an initializer ("Identity ... getMemoryShapes"). Each such node is
// replaced by a copy of the initializer under the node's output name; nothing else changes.
// Uses libonnx's protobuf classes (libonnx-dev). Not collective.
#include <filesystem>
#include <string>

namespace suite::rice {

struct ImportableOnnx {
  std::string bytes;    // the model to hand to cv::dnn::readNetFromONNX(buffer)
  int identities = 0;   // Identity nodes of initializers replaced
  bool parsed = false;  // false: protobuf could not read the file; `bytes` are the file as it is
};

// InputError naming the file when it cannot be read.
ImportableOnnx importable_onnx(const std::filesystem::path& file);

}  // namespace suite::rice
