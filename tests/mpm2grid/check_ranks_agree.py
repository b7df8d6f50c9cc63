"""Two mpm2grid runs of one scene, on 1 and on 2 ranks, agree to round-off (docs/methods/mpm2grid.md,
"Decomposition and performance design"): every column of series.csv and every particle's
position in the last particle file. The decomposition changes only the order in which P2G adds
particles into a node (its own particles first, then the halo sum) and the order of the global
sums, so the two runs differ by round-off that the steps carry along: about 1e-12 m after 3,600
steps of the dam scene. The tolerance, 1e-9 relative (positions: 1e-9 of the domain's size), is
a thousand times that and a million times below any modelling error; a wrong halo sum, a particle
lost or duplicated in migration, or a ghost node left with partial sums gives errors of percent.
The 2-rank run must really be decomposed: particles on both ranks, halo traffic.
  check_ranks_agree.py ONE_RANK_DIR TWO_RANK_DIR"""
import csv
import glob
import json
import math
import os
import sys

import h5py
import numpy as np

one, two = sys.argv[1], sys.argv[2]


def series(d):
    with open(os.path.join(d, "series.csv")) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:] if r])


head, a = series(one)
_, b = series(two)
assert a.shape == b.shape, f"series.csv: {a.shape} rows/columns on 1 rank, {b.shape} on 2"
worst = 0.0
for k, name in enumerate(head):
    for x, y in zip(a[:, k], b[:, k]):
        if math.isnan(x) and math.isnan(y):
            continue
        scale = max(np.abs(a[:, k][np.isfinite(a[:, k])]).max(), 1e-300)
        err = abs(x - y) / scale
        worst = max(worst, err)
        assert err <= 1e-9, f"{name}: {x!r} on 1 rank, {y!r} on 2 ranks (relative {err:.2e} > 1e-9)"
print(f"series.csv: {a.shape[0]} rows x {a.shape[1]} columns agree, largest relative difference {worst:.2e}")

last = sorted(os.path.basename(p) for p in glob.glob(os.path.join(one, "particles", "*.h5")))[-1]
with h5py.File(os.path.join(one, "particles", last)) as f1, h5py.File(os.path.join(two, "particles", last)) as f2:
    extent = max(np.ptp(f1[s]["position"][:], axis=0).max() for s in ("water", "soil") if s in f1)
    for s in ("water", "soil"):
        if s not in f1:
            continue
        p, q = f1[s]["position"][:], f2[s]["position"][:]
        assert p.shape == q.shape, f"{last}: {len(p)} {s} particles on 1 rank, {len(q)} on 2"
        # Sorted by position rounded to 1e-6 of the domain: particles of one lattice column share x,
        # and round-off alone must not change which of them comes first.
        key = lambda r: np.lexsort(np.round(r / (1e-6 * extent)).T[::-1])
        p, q = p[key(p)], q[key(q)]
        err = np.abs(p - q).max() / extent
        assert err <= 1e-9, f"{last}: {s} positions differ by {err:.2e} of the domain (> 1e-9)"
        print(f"{last}: {len(p)} {s} particles at the same places (largest difference {err:.2e} of the domain)")

with open(os.path.join(two, "run.json")) as f:
    dd = json.load(f)["decomposition"]
assert dd["ranks"] == 2 and min(dd["particles_per_rank"]) > 0, f"not decomposed: {dd}"
assert dd["halo_bytes_per_step"] > 0, f"no halo traffic: {dd}"
print(f"2 ranks: particles per rank {dd['particles_per_rank']}, halo {dd['halo_bytes_per_step']:.0f} bytes/step, "
      f"{dd['migrated_particles_per_step']:.2f} particles migrated/step, {dd['rebalances']} rebalances")
