#include "core/run/guarded_main.hpp"

#include <cstdio>
#include <exception>

#include "core/errors.hpp"

namespace suite {

int guarded_main(const mpi::Comm& world, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    if (world.is_root()) std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error on rank %d: %s\n", world.rank(), e.what());
  } catch (...) {
    std::fprintf(stderr, "internal error on rank %d: unknown exception\n", world.rank());
  }
  std::fflush(stderr);
  if (world.size() > 1) MPI_Abort(world.raw(), 1);
  return 1;
}

}  // namespace suite
