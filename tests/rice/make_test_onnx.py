#!/usr/bin/python3
"""A tiny ONNX network with hand-chosen weights, for testing `riceasv classify --onnx` (docs/rice.md,
"A network of your own (ONNX)"). A test fixture, not a trained model: it separates the renderer's
low / medium / high grades by one statistic, the gel's area against the kernel's in the crop.

    make_test_onnx.py OUT_DIR [--classes N]     writes OUT_DIR/net.onnx and OUT_DIR/net.json

Input: 1 x 1 x 60 x 60, a 12 mm grey crop around the grain, pixel / 255 (mean 0, std 1).
  Conv 1x1 (2 channels) + Relu, Conv 1x1 (-1, +1) + Relu, Conv 1x1 (-1, +1):
      min(relu(K (x - t) + 1/2), 1) = 1 - relu(1 - relu(K (x - t) + 1/2)) for t = T_GRAIN and
      T_KERNEL, a ramp from 0 to 1 over t -/+ 1/(2K): a soft "above t". Only Conv and Relu (every
      exporter writes them and OpenCV 4.6 imports them; its Clip does not take opset 11's min/max
      inputs), and every pixel off the ramp gives exactly 0 or 1, so float32 stays exact to ~1e-7;
  GlobalAveragePool: the share of the crop above each level, G (grain: gel or kernel) and K (kernel);
  Gemm to 3 scores, linear in G and K with the gel share G - K:
      low    C (-(G - K) + R_LOW K)      > medium (0) when gel / kernel < R_LOW
      medium 0
      high   C ((G - K) - R_HIGH K)      > medium (0) when gel / kernel > R_HIGH
  Softmax over the 3 scores.
The levels: the renderer's dish is grey 18, its gel 80-105 and its kernels 195-230 (grade 6's
remnant 70-80% of that), so T_GRAIN = 0.2 (51) lies between dish and gel and T_KERNEL = 0.6 (153)
between gel and kernel. The ratios: on these crops (blurred kernel edges count partly as gel) the gel
share over the kernel share of 24 rendered grains per grade (seed 5, 0.02 mm, not the test's set)
ran 0.11-0.18 (grade 2), 0.29-0.65 (3), 0.88-1.58 (4), 1.55-2.51 (5), 8.8-170 (6), no kernel (7);
R_LOW = 0.75 and R_HIGH = 4 lie between grades 3 and 4 and between 5 and 6, near the geometric means
of the neighbouring extremes. C = 150 makes the scores of a typical grain (shares of a few % of the
crop) a clear softmax.
--classes N (N != 3) writes a net.json naming N classes, for the test of a mismatched output.
"""
import json
import sys
from pathlib import Path

import numpy as np
try:
    import onnx
    from onnx import TensorProto, helper, numpy_helper
except ImportError:
    sys.exit(f"{sys.argv[0]}: needs Debian's python3-onnx (./suite setup, or apt-get install python3-onnx)")

SIZE, CROP_MM = 60, 12.0
K, T_GRAIN, T_KERNEL = 10.0, 0.2, 0.6
R_LOW, R_HIGH, C = 0.75, 4.0, 150.0
CLASSES = ["low", "medium", "high"]


def weights():
    """The parameters: conv1 weight (2,1,1,1) and bias (2), conv2 and conv3 weight (2,2,1,1) and bias
    (2), gemm weight (3,2) and bias (3)."""
    conv1_w = np.full((2, 1, 1, 1), K, dtype=np.float32)
    conv1_b = np.array([-K * T_GRAIN + 0.5, -K * T_KERNEL + 0.5], dtype=np.float32)
    flip_w = -np.eye(2, dtype=np.float32)[:, :, None, None]  # 1 - v, channel by channel
    flip_b = np.ones(2, dtype=np.float32)
    grain, kernel = np.array([1.0, 0.0]), np.array([0.0, 1.0])  # the pooled channels: G, K
    gel = grain - kernel
    gemm_w = C * np.stack([-gel + R_LOW * kernel, np.zeros(2), gel - R_HIGH * kernel])
    return (conv1_w, conv1_b, flip_w, flip_b, flip_w, flip_b, gemm_w.astype(np.float32),
            np.zeros(3, dtype=np.float32))


def build():
    params = dict(zip(["conv1_w", "conv1_b", "conv2_w", "conv2_b", "conv3_w", "conv3_b", "gemm_w", "gemm_b"],
                      weights()))
    nodes = [
        helper.make_node("Conv", ["input", "conv1_w", "conv1_b"], ["levels"], kernel_shape=[1, 1]),
        helper.make_node("Relu", ["levels"], ["above"]),
        helper.make_node("Conv", ["above", "conv2_w", "conv2_b"], ["below"], kernel_shape=[1, 1]),
        helper.make_node("Relu", ["below"], ["not_above"]),
        helper.make_node("Conv", ["not_above", "conv3_w", "conv3_b"], ["ramps"], kernel_shape=[1, 1]),
        helper.make_node("GlobalAveragePool", ["ramps"], ["pooled"]),
        helper.make_node("Flatten", ["pooled"], ["shares"], axis=1),
        helper.make_node("Gemm", ["shares", "gemm_w", "gemm_b"], ["logits"], transB=1),
        helper.make_node("Softmax", ["logits"], ["scores"], axis=1),
    ]
    graph = helper.make_graph(
        nodes, "riceasv_test_gel_ratio",
        [helper.make_tensor_value_info("input", TensorProto.FLOAT, ["N", 1, SIZE, SIZE])],
        [helper.make_tensor_value_info("scores", TensorProto.FLOAT, ["N", len(CLASSES)])],
        initializer=[numpy_helper.from_array(a, n) for n, a in params.items()])
    model = helper.make_model(graph, producer_name="riceasv tests/rice/make_test_onnx.py",
                              opset_imports=[helper.make_opsetid("", 13)])
    model.ir_version = 7
    onnx.checker.check_model(model)
    return model


def main():
    out = Path(sys.argv[1])
    classes = CLASSES
    if "--classes" in sys.argv:
        n = int(sys.argv[sys.argv.index("--classes") + 1])
        classes = [f"class{k}" for k in range(n)]
    out.mkdir(parents=True, exist_ok=True)
    onnx.save(build(), str(out / "net.onnx"))
    spec = {"format": "riceasv onnx classifier", "version": 1,
            "description": "test fixture (tests/rice/make_test_onnx.py): hand-set weights, not a trained model",
            "classes": classes,
            "input": {"width": SIZE, "height": SIZE, "channels": 1},
            "crop_mm": CROP_MM,
            "normalisation": {"mean": [0.0], "std": [1.0]},
            "output": "probabilities"}
    (out / "net.json").write_text(json.dumps(spec, indent=2) + "\n")


if __name__ == "__main__":
    main()
