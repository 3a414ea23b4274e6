#pragma once
// Boussinesq natural convection: Taylor-Hood Q2/Q1 velocity/pressure with Q2 temperature,
// inertia included, Newton's method with the exact Jacobian, sparse direct solve (UMFPACK).
// Steady (continuation in Ra when needed, nested iteration over the refinement levels) or in
// time (BDF2, first step BDF1, one Newton solve per step on the finest mesh). Instantiated for
// dim = 2 (boussinesq_2d.cpp) and 3 (boussinesq_3d.cpp; serial and direct, so only thin boxes
// such as one periodic in z). Setting the environment variable TWINFLOW_NEWTON_DEBUG prints every
// Newton iteration.

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <filesystem>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum {

template <int dim> class BoussinesqProblem {
public:
  explicit BoussinesqProblem(const ContinuumParameters& parameters);

  // The algorithm: mesh; steady: per refinement level setup, Newton (with continuation in Ra
  // on the first level); in time: march on the finest mesh; postprocess; fields into
  // `output_dir` unless it is empty (in time: snapshots as a series).
  ContinuumResult run(const std::filesystem::path& output_dir);

  // Solution access for tests: components u_0..u_{dim-1}, p, T at a point; the whole vector.
  dealii::Vector<double> value_at(const dealii::Point<dim>& point) const;
  const dealii::Vector<double>& solution() const { return solution_; }
  unsigned long n_dofs() const { return dof_handler_.n_dofs(); }

private:
  void make_coarse_mesh();
  void setup_dofs();
  void make_constraints();
  void initial_guess(); // at rest; T: the expression of the case or the conduction profile
  // Steady: nested iteration, one MeshLevel per refinement level.
  void solve_on_each_level(ContinuumResult& result);
  // In time: BDF2 from the initial state to the end time; time series and field snapshots.
  void march_in_time(const std::filesystem::path& dir, ContinuumResult& result);
  // Residual (always) and Jacobian (if `with_jacobian`) at `evaluation_point_` for gravity
  // scaled by `gravity_factor`, with the time derivatives of the current step when in time;
  // returns the residual norm.
  double assemble(bool with_jacobian, double gravity_factor);
  void solve_linear_system();
  // Newton iterations at one gravity factor; false if they did not converge.
  bool newton(double gravity_factor, int& iterations);
  // Reaches the full gravity in steps of the Rayleigh number (10x; halved on failure).
  void solve_with_continuation();
  void refine_mesh_and_transfer();
  void normalize_pressure(); // zero mean, after the last solve
  void postprocess(ContinuumResult& result) const;
  TimeSample sample(int step, int newton_iterations) const;
  void stream_function(ContinuumResult& result) const;
  void output_fields(const std::filesystem::path& dir, ContinuumResult& result) const;
  void attach_fields(dealii::DataOut<dim>& data_out) const;

  ContinuumParameters prm_;
  DimensionlessNumbers numbers_;
  dealii::Triangulation<dim> triangulation_;
  dealii::FESystem<dim> fe_;
  dealii::DoFHandler<dim> dof_handler_;
  dealii::AffineConstraints<double> nonzero_constraints_; // boundary values of the solution
  dealii::AffineConstraints<double> zero_constraints_;    // the same, homogeneous: updates

  dealii::SparsityPattern sparsity_pattern_;
  dealii::SparseMatrix<double> jacobian_;
  dealii::SparseDirectUMFPACK direct_solver_;
  dealii::Vector<double> solution_, evaluation_point_, newton_update_, residual_;
  // In time: d/dt x ~ time_a0_ x + history_ (boussinesq_kernel.hpp); time_a0_ = 0 when steady.
  double time_a0_ = 0, dt_ = 0;
  dealii::Vector<double> history_;

  PhaseTimes times_;
  int level_ = 0;
  int newton_iterations_ = 0;
  std::vector<double> continuation_rayleigh_;
};

} // namespace twinflow::continuum
