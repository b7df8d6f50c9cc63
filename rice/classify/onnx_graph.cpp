#include "rice/classify/onnx_graph.hpp"

#include <fmt/format.h>
#include <onnx/onnx_pb.h>

#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "core/errors.hpp"

namespace suite::rice {

ImportableOnnx importable_onnx(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(fmt::format("cannot read model file '{}'; check the path and its permissions", file.string()));
  ImportableOnnx out;
  out.bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  onnx::ModelProto model;
  if (!model.ParseFromString(out.bytes)) return out;
  out.parsed = true;
  auto* graph = model.mutable_graph();
  std::map<std::string, int> initializer;  // name -> index
  for (int i = 0; i < graph->initializer_size(); ++i) initializer[graph->initializer(i).name()] = i;
  google::protobuf::RepeatedPtrField<onnx::NodeProto> kept;
  for (const auto& node : graph->node()) {
    const auto source = node.op_type() == "Identity" && node.input_size() == 1 && node.output_size() == 1
                            ? initializer.find(node.input(0))
                            : initializer.end();
    if (source == initializer.end()) {
      *kept.Add() = node;
      continue;
    }
    onnx::TensorProto copy = graph->initializer(source->second);
    copy.set_name(node.output(0));
    *graph->add_initializer() = copy;
    ++out.identities;
  }
  if (out.identities == 0) return out;
  graph->mutable_node()->Swap(&kept);
  out.bytes.clear();
  model.SerializeToString(&out.bytes);
  return out;
}

}  // namespace suite::rice
