#pragma once
// Steady Boussinesq natural convection: Taylor-Hood Q2/Q1 velocity/pressure with Q2 temperature,
// inertia included, Newton's method with the exact Jacobian (continuation in Ra when needed),
// sparse direct solve (UMFPACK). Instantiated for dim = 2 (boussinesq_2d.cpp) and 3
// (boussinesq_3d.cpp; serial and direct, so only thin boxes such as one periodic in z).
// Setting the environment variable TWINFLOW_NEWTON_DEBUG prints every Newton iteration.

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <filesystem>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum {

template <int dim> class BoussinesqProblem {
public:
  explicit BoussinesqProblem(const ContinuumParameters& parameters);

  // The algorithm: mesh, then per refinement level setup, Newton (with continuation in Ra on
  // the first level), postprocess; fields into `output_dir` unless it is empty.
  ContinuumResult run(const std::filesystem::path& output_dir);

  // Solution access for tests: components u_0..u_{dim-1}, p, T at a point.
  dealii::Vector<double> value_at(const dealii::Point<dim>& point) const;
  unsigned long n_dofs() const { return dof_handler_.n_dofs(); }

private:
  void make_coarse_mesh();
  void setup_dofs();
  void make_constraints();
  void initial_guess();
  // Residual (always) and Jacobian (if `with_jacobian`) at `evaluation_point_` for gravity
  // scaled by `gravity_factor`; returns the residual norm.
  double assemble(bool with_jacobian, double gravity_factor);
  void solve_linear_system();
  // Newton iterations at one gravity factor; false if they did not converge.
  bool newton(double gravity_factor, int& iterations);
  // Reaches the full gravity in steps of the Rayleigh number (10x; halved on failure).
  void solve_with_continuation();
  void refine_mesh_and_transfer();
  void normalize_pressure(); // zero mean, after the last solve
  void postprocess(ContinuumResult& result) const;
  double volume_nusselt() const;
  void wall_nusselt(ContinuumResult& result) const;
  void midline_maxima(ContinuumResult& result) const;
  void stream_function(ContinuumResult& result) const;
  void output_fields(const std::filesystem::path& dir, ContinuumResult& result) const;

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

  PhaseTimes times_;
  int level_ = 0;
  int newton_iterations_ = 0;
  std::vector<double> continuation_rayleigh_;
};

} // namespace twinflow::continuum
