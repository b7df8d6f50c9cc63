#!/usr/bin/env bash
# The repository stands on its own: no tracked file refers to a folder beside the clone (the
# project's private shared/ folder of specs and reference data, or a variable that pointed there).
# Everything a build, test, demo, benchmark or doc reads lives in the repository; reference data
# in data/ (data/README.md).
#   stands_alone.sh REPOSITORY_ROOT
set -euo pipefail
root=$1
cd "$root"
# The patterns are assembled so that this file does not match itself.
dots='\.\.'
patterns=("$dots/shared" "SUITE_""SHARED_DIR" "shared/(reference|spec|background|DESIGN)")
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  list_files() { git ls-files -z; }
else  # an exported tree without .git: every file but build outputs
  list_files() { find . -path ./build -prune -o -type f -print0 | sed -z 's|^\./||'; }
fi
found=0
for p in "${patterns[@]}"; do
  if hits=$(list_files | xargs -0 grep -n -I -E -- "$p" 2>/dev/null); then
    echo "files refer to a path outside the repository (pattern '$p'):"
    echo "$hits" | sed 's/^/  /'
    found=1
  fi
done
if [ $found = 1 ]; then
  echo "FAIL: put what they read into the repository (data/ with a line in data/README.md, docs/) and cite that"
  exit 1
fi
echo "no tracked file refers to a path outside the repository"
