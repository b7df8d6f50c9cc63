#!/usr/bin/env bash
# A study over MPI ranks (rank 0 hands out evaluations, the others evaluate) gives the same table
# as the threaded run, and resumes over MPI after a kill to the same table again.
#   check_mpi_study.sh WORKDIR SPEC STUDY MPIEXEC...
set -euo pipefail
work=$1 spec=$2 study=$3
shift 3
rm -rf "$work"
"$study" run "$spec" --out "$work/threads" --log-level warn output.plot=false
"$@" "$study" run "$spec" --out "$work/mpi" --log-level warn output.plot=false
cmp "$work/threads/tabular.dat" "$work/mpi/tabular.dat"
cmp "$work/threads/analysis.json" "$work/mpi/analysis.json"
head -n 50 "$work/mpi/ledger.jsonl" > "$work/l" && mv "$work/l" "$work/mpi/ledger.jsonl"
rm "$work/mpi/tabular.dat"
"$@" "$study" resume "$work/mpi" --log-level warn
cmp "$work/threads/tabular.dat" "$work/mpi/tabular.dat"
echo "MPI study: same table as the threaded run, also after a resume"
