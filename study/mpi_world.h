// The MPI ranks a command was started on (`mpirun -n P spall dataset run ...`), or a world of
// one rank. Open MPI's C API is used only inside mpi_world.cc; a build without MPI (or a process
// not started by an MPI launcher) gets rank 0 of 1 and no MPI calls at all.
#pragma once

namespace spallkit::study {

class MpiWorld {
 public:
  // Initialises MPI when spallkit was built with it and the environment shows an MPI launcher
  // (Open MPI's OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK); finalises in the destructor.
  MpiWorld();
  ~MpiWorld();
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool active() const { return active_; }  // MPI initialised by this object

  void Barrier() const;
  long long Sum(long long value) const;  // over all ranks (every rank gets the total)
  // Ends every rank with this exit code (one rank's error would otherwise leave the others
  // waiting in a barrier).
  [[noreturn]] void Abort(int code) const;

  static bool BuiltWithMpi();
  static bool LaunchedByMpi();
  // The number of processes the launcher started (its environment; 1 when not launched by one),
  // known even to a build without MPI.
  static int LauncherSize();

 private:
  int rank_ = 0, size_ = 1;
  bool active_ = false;
};

}  // namespace spallkit::study
