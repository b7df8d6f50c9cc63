#!/usr/bin/python3
"""`riceasv classify --onnx` end to end with the test network of make_test_onnx.py:
 (a) OpenCV dnn's scores (CLASSIFY_DIR/scores.csv, 9 digits) equal the same network evaluated here in
     numpy (its ops read from NET_DIR/net.onnx, its input the crops riceasv wrote with --crops,
     normalised as net.json says) to 1e-5 for every grain; each crop is crop_mm / pixel size pixels
     centred on the grain's centroid within half a pixel (plus classes.csv's 0.05 px rounding);
 (b) its classes on a rendered set are right (each grain's photograph's grade in truth.csv) for
     more than MIN_ACCURACY of the ok grains, and classes.csv, scores.csv and classify.json agree.
Prints the largest score difference and the accuracy per class and overall.
    check_onnx.py NET_DIR CLASSIFY_DIR RENDER_DIR PIXEL_SIZE_MM MIN_ACCURACY
"""
import json
import sys
from pathlib import Path

import matplotlib.image
import numpy as np
try:
    import onnx
    from onnx import numpy_helper
except ImportError:
    sys.exit(f"{sys.argv[0]}: needs Debian's python3-onnx (./suite setup, or apt-get install python3-onnx)")

from rice_tables import class_accuracy, table  # noqa: E402



def run_numpy(model, x):
    """Evaluates the graph's nodes in order in float64 (the ops make_test_onnx.py uses)."""
    values = {i.name: numpy_helper.to_array(i).astype(np.float64) for i in model.graph.initializer}
    values[model.graph.input[0].name] = x
    for node in model.graph.node:
        a = {at.name: onnx.helper.get_attribute_value(at) for at in node.attribute}
        i = [values[n] for n in node.input]
        if node.op_type == "Conv":
            assert list(a["kernel_shape"]) == [1, 1], "only 1x1 convolutions"
            y = np.einsum("oc,nchw->nohw", i[1][:, :, 0, 0], i[0]) + i[2][None, :, None, None]
        elif node.op_type == "Relu":
            y = np.maximum(i[0], 0)
        elif node.op_type == "GlobalAveragePool":
            y = i[0].mean(axis=(2, 3), keepdims=True)
        elif node.op_type == "Flatten":
            y = i[0].reshape(i[0].shape[0], -1)
        elif node.op_type == "Gemm":
            y = i[0] @ (i[1].T if a.get("transB", 0) else i[1]) + i[2]
        elif node.op_type == "Softmax":
            e = np.exp(i[0] - i[0].max(axis=1, keepdims=True))
            y = e / e.sum(axis=1, keepdims=True)
        else:
            raise SystemExit(f"FAIL op {node.op_type} not evaluated here")
        values[node.output[0]] = y
    return values[model.graph.output[0].name]


net, classified, rendered = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
pixel, minimum = float(sys.argv[4]), float(sys.argv[5])
failures = []
check = lambda ok, what: ok or failures.append(what)
spec = json.loads((net / "net.json").read_text())
model = onnx.load(str(net / "net.onnx"))
names = spec["classes"]
mean, std = np.array(spec["normalisation"]["mean"]), np.array(spec["normalisation"]["std"])
side = round(spec["crop_mm"] / pixel)

scores = table(classified / "scores.csv")
classes = table(classified / "classes.csv")
graded = [c for c in classes if c["status"] != "failed"]
check(len(scores) == len(graded) > 0, f"{len(scores)} rows in scores.csv, {len(graded)} grains in classes.csv")
worst = 0.0
for s, c in zip(scores, graded):
    where = f"{Path(s['image']).name} grain {s['grain']}"
    check((s["image"], s["grain"]) == (c["image"], c["grain"]), f"{where}: scores.csv and classes.csv disagree")
    x0, y0, n = int(s["crop_x0"]), int(s["crop_y0"]), int(s["crop_px"])
    check(n == side, f"{where}: crop of {n} px, not {side}")
    for origin, centre in ((x0, float(c["x_px"])), (y0, float(c["y_px"]))):
        check(abs(origin + n / 2 - centre) <= 0.55, f"{where}: crop at {origin} is not centred on {centre}")
    crop = matplotlib.image.imread(classified / "crops" / f"{Path(s['image']).stem}_g{s['grain']}.png")
    pixels = np.round(crop * 255) if crop.dtype != np.uint8 else crop.astype(np.float64)  # PNG read as 0..1
    check(pixels.shape == (spec["input"]["height"], spec["input"]["width"]), f"{where}: crop shape {pixels.shape}")
    x = ((pixels / 255 - mean[0]) / std[0])[None, None]
    expected = run_numpy(model, x)[0]
    got = np.array([float(s[f"score_{k}"]) for k in names])
    worst = max(worst, float(np.abs(got - expected).max()))
    best = int(np.argmax(got))
    check(c["class"] == names[best] and abs(float(c["share"]) - got[best]) <= 5e-4,
          f"{where}: classes.csv says {c['class']} {c['share']}, scores.csv {names[best]} {got[best]}")
check(worst <= 1e-5, f"OpenCV dnn and numpy differ by {worst:.2e} (more than 1e-5)")
print(f"largest |OpenCV dnn - numpy| over {len(scores)} grains: {worst:.2e}")

ok = [c for c in classes if c["status"] == "ok"]
summary = json.loads((classified / "classify.json").read_text())
check(summary["model_type"] == "onnx", f"classify.json model_type {summary['model_type']}")
check(sum(summary["counts"].values()) == len(ok), "classify.json counts do not sum to the ok grains")
accuracy = class_accuracy(ok, rendered / "truth.csv", names, "onnx", share_name="score")
print(f"onnx accuracy {accuracy:.1%} of {len(ok)} ok grains (minimum {minimum:.0%})")
check(accuracy > minimum, f"accuracy {accuracy:.1%} not above {minimum:.0%}")
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
