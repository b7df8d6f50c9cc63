#!/usr/bin/python3
"""A small network as a lab would bring one to `riceasv train --model-type pretrained` (docs/rice.md,
"Fine-tuning a pretrained network"): written with PyTorch, scripted with torch.jit.script and saved
as OUT/net.pt, with OUT/net.json in the ONNX path's convention (three classes, 64 x 64 RGB crops of
12 mm, ImageNet's normalisation, logits). Its weights are PyTorch's seeded initialisation standing in
for pretrained ones (none can be downloaded here): the test checks that the suite fine-tunes and runs
a TorchScript network end to end, not what ImageNet weights are worth.
    make_torchscript_net.py OUT [--classes N]
Needs Debian's python3-torch (./suite setup)."""
import json
import sys
from pathlib import Path

try:
    import torch
    from torch import nn
except ImportError:
    sys.exit(f"{sys.argv[0]}: needs Debian's python3-torch (./suite setup)")


def block(cin, cout):
    return [nn.Conv2d(cin, cout, 3, padding=1), nn.BatchNorm2d(cout), nn.ReLU()]


def main():
    out = Path(sys.argv[1])
    classes = ["low", "medium", "high"]
    if "--classes" in sys.argv:
        classes = [f"class{k}" for k in range(int(sys.argv[sys.argv.index("--classes") + 1]))]
    torch.manual_seed(3)
    net = nn.Sequential(*block(3, 8), nn.MaxPool2d(2), *block(8, 16), nn.MaxPool2d(2), *block(16, 32),
                        nn.AdaptiveAvgPool2d(1), nn.Flatten(), nn.Linear(32, len(classes)))
    net.eval()
    out.mkdir(parents=True, exist_ok=True)
    torch.jit.script(net).save(str(out / "net.pt"))
    spec = {"format": "riceasv onnx classifier", "version": 1,
            "description": "test fixture (tests/rice/make_torchscript_net.py): seeded initial weights",
            "classes": classes,
            "input": {"width": 64, "height": 64, "channels": 3, "colour_order": "rgb"},
            "crop_mm": 12,
            "normalisation": {"mean": [0.485, 0.456, 0.406], "std": [0.229, 0.224, 0.225]},
            "output": "logits"}
    (out / "net.json").write_text(json.dumps(spec, indent=2) + "\n")


if __name__ == "__main__":
    main()
