#!/usr/bin/python3
"""A real ResNet-18 through `riceasv classify --onnx`, as a lab would bring one (docs/rice.md, "A
network of your own (ONNX)"): torchvision's ResNet-18 with a three-class head, exported by PyTorch's
own torch.onnx.export (opset 13) with ImageNet's input convention (224 x 224 RGB, ImageNet mean and
std, logits out). Its weights are torchvision's seeded initialisation, not trained ones (no weights
can be downloaded here), so only the arithmetic is checked, not the classes.

    resnet_onnx.py export NET_DIR
        writes NET_DIR/net.onnx and NET_DIR/net.json
    resnet_onnx.py check NET_DIR CLASSIFY_DIR
        runs the same network in PyTorch on every crop riceasv wrote (--crops) and asks that
        OpenCV dnn's probabilities in CLASSIFY_DIR/scores.csv agree to 1e-4 (float32 through 18
        convolutions and batch normalisations summed in another order: differences of 1e-6 are
        expected; a wrong channel order or normalisation moves them by 1e-2 or more).
Needs Debian's python3-torch and python3-torchvision (./suite setup)."""
import csv
import json
import sys
from pathlib import Path

import numpy as np
try:
    import torch
    import torchvision
except ImportError:
    sys.exit(f"{sys.argv[0]}: needs Debian's python3-torch and python3-torchvision (./suite setup)")
import matplotlib.image

MEAN, STD = [0.485, 0.456, 0.406], [0.229, 0.224, 0.225]
CLASSES = ["low", "medium", "high"]


def network():
    torch.manual_seed(7)
    net = torchvision.models.resnet18(weights=None, num_classes=len(CLASSES))
    net.eval()
    return net


def export(out):
    out.mkdir(parents=True, exist_ok=True)
    torch.onnx.export(network(), torch.zeros(1, 3, 224, 224), str(out / "net.onnx"), opset_version=13,
                      input_names=["input"], output_names=["logits"])
    spec = {"format": "riceasv onnx classifier", "version": 1,
            "description": "test fixture (tests/rice/resnet_onnx.py): torchvision ResNet-18, seeded initial "
                           "weights, not trained",
            "classes": CLASSES,
            "input": {"width": 224, "height": 224, "channels": 3, "colour_order": "rgb"},
            "crop_mm": 12,
            "normalisation": {"mean": MEAN, "std": STD},
            "output": "logits"}
    (out / "net.json").write_text(json.dumps(spec, indent=2) + "\n")


def check(net_dir, classified):
    net = network()
    rows = [r for r in csv.DictReader(l for l in (classified / "scores.csv").read_text().splitlines()
                                      if not l.startswith("#"))]
    if not rows:
        sys.exit("FAIL no grains in scores.csv")
    worst = 0.0
    for r in rows:
        crop = classified / "crops" / f"{Path(r['image']).stem}_g{r['grain']}.png"
        rgb = matplotlib.image.imread(str(crop))[:, :, :3].astype(np.float64)  # PNG as written: 0..1, RGB
        x = (rgb - np.array(MEAN)) / np.array(STD)
        with torch.no_grad():
            p = torch.softmax(net(torch.tensor(x.transpose(2, 0, 1)[None], dtype=torch.float32)), 1)[0].numpy()
        opencv = np.array([float(r[f"score_{c}"]) for c in CLASSES])
        worst = max(worst, float(np.abs(p - opencv).max()))
    print(f"ResNet-18 through OpenCV dnn against PyTorch on {len(rows)} crops: largest probability difference "
          f"{worst:.2e} (bound 1e-4)")
    if worst > 1e-4:
        sys.exit(f"FAIL OpenCV's probabilities differ from PyTorch's by {worst:.2e}")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "export":
        export(Path(sys.argv[2]))
    elif len(sys.argv) == 4 and sys.argv[1] == "check":
        check(Path(sys.argv[2]), Path(sys.argv[3]))
    else:
        sys.exit(__doc__)
