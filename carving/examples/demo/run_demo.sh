#!/usr/bin/env bash
# The seed-phenotyping part of the suite's main job: a small seed batch measured on MPI ranks.
#   run_demo.sh BIN_DIR OUT_DIR [MPIEXEC...]      e.g. run_demo.sh build/release/bin out mpiexec -n 2
#
# 1. `seedcarve render` draws four synthetic seeds of known volume through the measuring camera:
#    a wheat-sized ellipsoid and a creased grain (36 turntable views), a boxy milo grain
#    (superellipsoid), and a wheat grain photographed from the top and the side (slicing).
# 2. The real Kansas State wheat grain (36 photographs, data/kstate_wheat_36view) joins them.
# 3. One row names a folder that does not exist: its row reports the failure, the batch goes on.
# 4. `seedcarve batch` measures them, rank 0 handing seeds to the other ranks; compare_truth.py
#    puts each measured volume beside the true one.
set -euo pipefail
BIN=$1 OUT=$2
shift 2
MPIEXEC=("$@")
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
synthetic=$root/carving/examples/synthetic
mkdir -p "$OUT/images"

manifest=$OUT/manifest.csv
echo "id,images,method,weight_mg,profile" > "$manifest"
# id, scene, weight (mg; a density of about 1.3 mg/mm^3 for the synthetic seeds)
for seed in wheat_ellipsoid:wheat_ellipsoid:51.2 creased_wheat:creased_grain:44.0 milo:milo_superellipsoid:30.5 \
            wheat_top_side:wheat_two_view:51.2; do
  IFS=: read -r id scene weight <<<"$seed"
  "$BIN/seedcarve" render "$synthetic/$scene.yaml" --out "$OUT/images/$id" --log-level warn
  method=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['method'])" "$OUT/images/$id/truth.json")
  if [ "$method" = slicing ]; then
    images="images/$id/top.png;images/$id/side.png"
  else
    images="images/$id"
  fi
  echo "$id,$images,$method,$weight,images/$id/profile.yaml" >> "$manifest"
done
kstate=$root/data/kstate_wheat_36view
if [ ! -d "$kstate/images" ]; then
  echo "[carving demo] $kstate/images is missing: the repository is incomplete (git checkout -- data)" >&2
  exit 1
fi
echo "kstate_wheat,$kstate/images,carving,,$root/carving/examples/profiles/kstate_wheat_turntable.yaml" >> "$manifest"
echo "missing_seed,images/no_such_folder,carving,,images/wheat_ellipsoid/profile.yaml" >> "$manifest"

"${MPIEXEC[@]}" "$BIN/seedcarve" batch "$manifest" --out "$OUT/batch"
/usr/bin/python3 "$here/compare_truth.py" "$OUT"
