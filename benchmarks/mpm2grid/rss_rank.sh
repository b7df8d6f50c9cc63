#!/usr/bin/env bash
# Runs one MPI rank (or a serial run) under /usr/bin/time and writes its peak resident set size
# (kB) to RSS_DIR/rss_rank<N>.txt, N the rank (Open MPI's OMPI_COMM_WORLD_RANK, MPICH's PMI_RANK).
#   [mpiexec -n P] rss_rank.sh RSS_DIR EXE ARGS...
set -euo pipefail
dir=$1
shift
rank=${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-0}}
exec /usr/bin/time -f %M -o "$dir/rss_rank$rank.txt" "$@"
