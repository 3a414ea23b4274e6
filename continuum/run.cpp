#include "continuum/run.hpp"

#include <stdexcept>

#include "continuum/boussinesq.hpp"
#include "continuum/boussinesq_distributed.hpp"
#include "continuum/compressible.hpp"
#include "continuum/heat_conduction.hpp"
#include "continuum/low_mach.hpp"

namespace twinflow::continuum {

ContinuumResult run(const ContinuumParameters& p, const std::filesystem::path& output_dir,
                    MPI_Comm comm) {
  check(p);
  if (p.model == Model::HeatConduction) {
    switch (p.dim) {
    case 1:
      return HeatConductionProblem<1>(p).run(output_dir);
    case 2:
      return HeatConductionProblem<2>(p).run(output_dir);
    default:
      return HeatConductionProblem<3>(p).run(output_dir);
    }
  }
  if (p.model == Model::LowMach) {
    if (p.dim == 2) return LowMachProblem<2>(p).run(output_dir);
    return LowMachProblem<3>(p).run(output_dir);
  }
  if (p.model == Model::Compressible) {
    // Here, not in check(): c_p may come from the transport stage after the case is read.
    if (!(p.heat_capacity > 1.0))
      throw std::invalid_argument(
          "continuum parameters: the compressible model needs c_p > k (c_V = c_p - k > 0)");
    if (p.dim == 2) return CompressibleProblem<2>(p).run(output_dir);
    return CompressibleProblem<3>(p).run(output_dir);
  }
  if (p.uses_iterative_solver()) return DistributedBoussinesqProblem<3>(p, comm).run(output_dir);
  if (p.dim == 2) return BoussinesqProblem<2>(p).run(output_dir);
  return BoussinesqProblem<3>(p).run(output_dir);
}

} // namespace twinflow::continuum
