#!/usr/bin/python3
"""Validates an XDMF time series the way ParaView reads it: the XML parses, it is a temporal
collection with increasing times, and every HDF5 DataItem names an existing dataset whose
shape equals the declared Dimensions. Usage: check_xdmf.py series.xmf n_steps"""
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import h5py


def main(path: Path, n_steps: int) -> int:
    root = ET.parse(path).getroot()  # raises on malformed XML
    assert root.tag == "Xdmf", root.tag
    series = root.find("Domain/Grid")
    assert series.get("CollectionType") == "Temporal", series.attrib
    steps = series.findall("Grid")
    assert len(steps) == n_steps, f"{len(steps)} steps, expected {n_steps}"
    times = [float(s.find("Time").get("Value")) for s in steps]
    assert times == sorted(times) and len(set(times)) == len(times), times
    checked = 0
    for step in steps:
        for grid in step.findall("Grid"):
            topo = grid.find("Topology")
            assert topo is not None and grid.find("Geometry") is not None, grid.get("Name")
            for item in grid.iter("DataItem"):
                assert item.get("Format") == "HDF", item.attrib
                file_name, dataset = item.text.strip().split(":", 1)
                dims = tuple(int(d) for d in item.get("Dimensions").split())
                with h5py.File(path.parent / file_name, "r") as f:
                    assert dataset in f, f"{file_name} has no {dataset}"
                    assert f[dataset].shape == dims, f"{file_name}:{dataset} {f[dataset].shape} != {dims}"
                checked += 1
            n_points = int(grid.find("Geometry/DataItem").get("Dimensions").split()[0])
            if topo.get("TopologyType") == "Polyvertex":
                assert int(topo.get("NumberOfElements")) == n_points
    print(f"{path}: {len(steps)} steps, {checked} datasets referenced and present")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), int(sys.argv[2])))
