#!/usr/bin/env bash
# Every file in data/ has its source, terms and derivation in data/README.md: each top-level
# entry of data/ (a file, or a folder such as kstate_wheat_36view/) is named there in backquotes.
#   check_data_sources.sh REPOSITORY_ROOT
set -euo pipefail
data=$1/data
missing=0
for entry in "$data"/*; do
  name=$(basename "$entry")
  [ "$name" = README.md ] && continue
  [ -d "$entry" ] && name="$name/"
  if ! grep -q -F "\`$name\`" "$data/README.md"; then
    echo "data/$name has no entry in data/README.md (source, terms of use, how it was derived)"
    missing=1
  fi
done
[ $missing = 0 ] || exit 1
echo "every entry of data/ is described in data/README.md"
