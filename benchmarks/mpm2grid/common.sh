# Sourced by the mpm2grid benchmark drivers: the binary, the MPI launcher, the results folder.
#   MPM2GRID   the executable (or the drivers' first argument); default build/release/bin/mpm2grid
#   MPIEXEC    the launcher of the 2-rank runs; default "mpiexec --allow-run-as-root --oversubscribe"
#   OUT        the results folder; default benchmarks/results/mpm2grid
#   NICE       a prefix for every run, e.g. "nice -n 19" for trial runs beside other work
#   KEEP_RUNS  1 keeps the runs' output folders (under $OUT/runs/<benchmark>/), else a temporary folder
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/benchmarks/mpm2grid
scenes=$root/solvers/mpm2grid/scenes
bin=${1:-${MPM2GRID:-$root/build/release/bin/mpm2grid}}
[[ $bin = /* ]] || bin=$PWD/$bin
[ -x "$bin" ] || { echo "no mpm2grid executable at $bin (pass it as the first argument or MPM2GRID)" >&2; exit 2; }
mpiexec_cmd=${MPIEXEC:-mpiexec --allow-run-as-root --oversubscribe}
out=${OUT:-$root/benchmarks/results/mpm2grid}
mkdir -p "$out"
nice_cmd=${NICE:-}
metrics=(/usr/bin/python3 "$here/mpm_metrics.py")
plot=/usr/bin/python3

# The folder the runs of benchmark $1 write into.
work_dir() {
  if [ "${KEEP_RUNS:-0}" = 1 ]; then
    work=$out/runs/$1
    rm -rf "$work" && mkdir -p "$work"
  else
    work=$(mktemp -d "/tmp/mpm2grid-bench-$1.XXXXXX")
    trap 'rm -rf "$work"' EXIT
  fi
}

# The machine, build and git hash, for the head of each Markdown table.
provenance() {
  echo "Machine: $(uname -n), $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')); load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)."
  echo "Binary: $bin ($(/usr/bin/python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d.get("build_type"), d.get("compiler"), d.get("cxx_flags"), "git", d.get("git_hash"))' "$1" 2>/dev/null || echo unknown)); repository at git $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown); $(date -u +%Y-%m-%dT%H:%MZ)${NICE:+; every run under \"$NICE\"}."
}

# run_one DIR RANKS ARGS...: one mpm2grid run into DIR on RANKS ranks, each rank's peak RSS in DIR.rss/;
# prints the exit status (0 completed, 2 stopped by an input error or a blow-up); stderr into DIR.err.
run_one() {
  local dir=$1 ranks=$2
  shift 2
  rm -rf "$dir" "$dir.rss" && mkdir -p "$dir.rss"
  local rc=0
  if [ "$ranks" = 1 ]; then
    $nice_cmd "$here/rss_rank.sh" "$dir.rss" "$bin" "$@" --out "$dir" --log-level warn 2> "$dir.err" || rc=$?
  else
    $nice_cmd $mpiexec_cmd -n "$ranks" "$here/rss_rank.sh" "$dir.rss" "$bin" "$@" --out "$dir" --log-level warn \
      2> "$dir.err" || rc=$?
  fi
  echo "$rc"
}

# check_run STATUS DIR: stops the driver, with the run's last words, unless STATUS (run_one's) is 0.
check_run() { [ "$1" = 0 ] || { echo "run $2 failed ($1): $(tail -2 "$2.err")" >&2; exit 1; }; }
