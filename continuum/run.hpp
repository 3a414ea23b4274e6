#pragma once
// Entry point of the continuum twin: picks the model and dimension, runs, returns the results.

#include <filesystem>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum {

// Fields (HDF5 + XDMF) go into `output_dir` unless it is empty; throws std::invalid_argument for
// inconsistent parameters (before any work) and std::runtime_error if a solve fails.
ContinuumResult run(const ContinuumParameters& parameters, const std::filesystem::path& output_dir);

} // namespace twinflow::continuum
