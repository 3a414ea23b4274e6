#pragma once
// Entry point of the continuum twin: picks the model and dimension, runs, returns the results.

#include <filesystem>

#include <deal.II/base/mpi.h>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum {

// Fields (HDF5 + XDMF) go into `output_dir` unless it is empty; throws std::invalid_argument for
// inconsistent parameters (before any work) and std::runtime_error if a solve fails. `comm`: the
// processes the distributed (iterative 3D) path shares the work over; the others run on one.
ContinuumResult run(const ContinuumParameters& parameters, const std::filesystem::path& output_dir,
                    MPI_Comm comm = MPI_COMM_WORLD);

} // namespace twinflow::continuum
