#!/bin/sh
# A singleton's Open MPI session folder (core/mpi/environment.hpp): after a clean exit none is
# left; one left by a process that no longer exists (a killed singleton) is removed by the next
# singleton; one whose process is alive stays, and so do folders of other names.
#   check_session_dirs.sh EXECUTABLE SCRATCH_DIR   (EXECUTABLE must accept --help)
set -eu
exe=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir"
sh -c 'exit 0' &
dead=$!
wait "$dead"
mkdir "$dir/suite-mpi.$dead.stale-folder" "$dir/suite-mpi.$$.live-folder" "$dir/suite-mpi.other-folder"
env -u OMPI_MCA_ess_singleton_isolated -u OMPI_MCA_orte_tmpdir_base TMPDIR="$dir" "$exe" --help > /dev/null
fail() { echo "FAIL: $*; left: $(ls "$dir" | tr '\n' ' ')"; exit 1; }
[ ! -e "$dir/suite-mpi.$dead.stale-folder" ] || fail "the folder of exited process $dead was kept"
[ -d "$dir/suite-mpi.$$.live-folder" ] || fail "the folder of live process $$ was removed"
[ -d "$dir/suite-mpi.other-folder" ] || fail "a folder of another name was removed"
[ "$(ls "$dir" | wc -l)" -eq 2 ] || fail "the singleton left its own session folder"
echo "session folders: stale removed, live and others kept, none left"
