#pragma once
// The distributed, iterative path of the steady Boussinesq solver (step-32/55/57 style), for 3D
// boxes that a direct solver cannot factorise: p4est parallel::distributed::Triangulation,
// Trilinos block matrices, Newton with the exact Jacobian (boussinesq_kernel.hpp), each Newton
// system solved by FGMRES with a block-triangular preconditioner:
//   pressure: S ~ -(1/eta) M_p (ILU of the pressure mass matrix),
//   velocity: AMG of the velocity block, temperature: AMG of the temperature block.
// Runs on one process or under mpirun. Steady or in time (BDF2 as the serial solver). Instantiated
// for dim = 3 (boussinesq_distributed_3d.cpp).

#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/numerics/data_out.h>

#include <filesystem>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum {

template <int dim> class DistributedBoussinesqProblem {
public:
  explicit DistributedBoussinesqProblem(const ContinuumParameters& parameters,
                                        MPI_Comm comm = MPI_COMM_WORLD);

  // Same algorithm as BoussinesqProblem::run: steady, nested iteration over the refinement
  // levels with continuation in Ra on the first; or in time on the finest mesh. Nu, wall Nu,
  // mid-line maxima, bins; fields into `output_dir` if not empty.
  // Not computed on this path: stream function, probes, local wall Nu under mpirun.
  ContinuumResult run(const std::filesystem::path& output_dir);

private:
  void make_mesh();
  void solve_on_each_level(ContinuumResult& result);
  void march_in_time(const std::filesystem::path& dir, ContinuumResult& result);
  TimeSample sample(int step, int newton_iterations) const;
  void attach_fields(dealii::DataOut<dim>& data_out) const;
  void setup_dofs();
  void make_constraints();
  void assemble_pressure_mass();
  void initial_guess();
  double assemble(bool with_jacobian, double gravity_factor);
  unsigned solve_linear_system(); // returns the FGMRES iterations
  bool newton(double gravity_factor, int& iterations);
  void solve_with_continuation();
  void refine_mesh_and_transfer();
  void normalize_pressure();
  void postprocess(ContinuumResult& result) const;
  void output_fields(const std::filesystem::path& dir, ContinuumResult& result) const;

  MPI_Comm comm_;
  ContinuumParameters prm_;
  DimensionlessNumbers numbers_;
  dealii::parallel::distributed::Triangulation<dim> triangulation_;
  dealii::FESystem<dim> fe_;
  dealii::DoFHandler<dim> dof_handler_;
  std::vector<dealii::IndexSet> owned_partitioning_, relevant_partitioning_;
  dealii::AffineConstraints<double> nonzero_constraints_, zero_constraints_;
  dealii::TrilinosWrappers::BlockSparseMatrix jacobian_;
  dealii::TrilinosWrappers::BlockSparseMatrix preconditioner_matrix_;   // (1,1): M_p / eta
  dealii::TrilinosWrappers::MPI::BlockVector solution_;                 // owned
  dealii::TrilinosWrappers::MPI::BlockVector evaluation_point_;         // ghosted
  dealii::TrilinosWrappers::MPI::BlockVector newton_update_, residual_; // owned
  // In time: d/dt x ~ time_a0_ x + history_ (ghosted; boussinesq_kernel.hpp).
  double time_a0_ = 0, dt_ = 0;
  dealii::TrilinosWrappers::MPI::BlockVector history_;

  PhaseTimes times_;
  int newton_iterations_ = 0;
  unsigned long linear_iterations_ = 0;
  double first_residual_ = 0; // scale of the absolute floor of the linear solves
  std::vector<double> continuation_rayleigh_;
};

} // namespace twinflow::continuum
