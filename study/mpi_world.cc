#include "study/mpi_world.h"

#include <algorithm>
#include <cstdlib>

#ifdef SPALLKIT_HAVE_MPI
// The C API only (Open MPI's and MPICH's mpi.h would otherwise pull in the deprecated C++ one).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace spallkit::study {

bool MpiWorld::BuiltWithMpi() {
#ifdef SPALLKIT_HAVE_MPI
  return true;
#else
  return false;
#endif
}

bool MpiWorld::LaunchedByMpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
}

int MpiWorld::LauncherSize() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 1;
}

MpiWorld::MpiWorld() {
#ifdef SPALLKIT_HAVE_MPI
  if (!LaunchedByMpi()) return;
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) return;
  MPI_Init(nullptr, nullptr);
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
#endif
}

MpiWorld::~MpiWorld() {
#ifdef SPALLKIT_HAVE_MPI
  if (active_) MPI_Finalize();
#endif
}

void MpiWorld::Barrier() const {
#ifdef SPALLKIT_HAVE_MPI
  if (active_) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

long long MpiWorld::Sum(long long value) const {
#ifdef SPALLKIT_HAVE_MPI
  if (active_) {
    long long total = 0;
    MPI_Allreduce(&value, &total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    return total;
  }
#endif
  return value;
}

void MpiWorld::Abort(int code) const {
#ifdef SPALLKIT_HAVE_MPI
  if (active_) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace spallkit::study
