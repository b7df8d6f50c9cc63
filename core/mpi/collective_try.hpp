#pragma once
// Turns an InputError raised on some ranks into the same InputError on every rank, so that
// main's error policy (print once on rank 0, exit 2; see run/guarded_main.hpp) never leaves a
// rank waiting in a collective call. Use it around work that only some ranks do, such as
// rank 0 opening an existing CSV file on restart. COLLECTIVE.
#include <string>
#include <utility>

#include "core/errors.hpp"
#include "core/mpi/comm.hpp"

namespace suite::mpi {

// Throws InputError(message of the lowest rank whose `local_problem` is not empty) on every
// rank, or returns if no rank has a problem. COLLECTIVE.
void agree_on_input_error(const Comm& comm, const std::string& local_problem);

template <class F>
void collective_try(const Comm& comm, F&& f) {
  std::string problem;
  try {
    std::forward<F>(f)();
  } catch (const InputError& e) {
    problem = e.what();
    if (problem.empty()) problem = "input error";
  }
  agree_on_input_error(comm, problem);
}

}  // namespace suite::mpi
