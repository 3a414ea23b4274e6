#pragma once
// Steady low-Mach-number natural convection of a variable-density fluid in a closed box (large
// temperature differences, beside the Boussinesq model). Same mesh, elements (Taylor-Hood Q2/Q1
// velocity/pressure + Q2 temperature), continuation and output as BoussinesqProblem; equations
// and the Newton method in low_mach.templates.hpp. Instantiated for dim = 2 (low_mach_2d.cpp) and
// 3 (low_mach_3d.cpp; serial and direct, thin boxes only). Steady (Newton) or, with an end time,
// transient by implicit Euler steps.
// TWINFLOW_NEWTON_DEBUG prints every Newton iteration.

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

namespace detail {
// Implicit Euler terms of the transient mode (Le Quere et al. 2005, with d/dt): the previous
// state and 1/dt; inverse_time_step = 0: steady.
struct LowMachTimeTerms {
  const dealii::Vector<double>* old_solution = nullptr;
  double old_pressure = 0;      // P at the previous time
  double inverse_time_step = 0; // 1/dt
};
} // namespace detail

template <int dim> class LowMachProblem {
public:
  explicit LowMachProblem(const ContinuumParameters& parameters);

  // Mesh, then per refinement level setup, Newton (continuation in Ra on the first level),
  // postprocess; fields into `output_dir` unless it is empty.
  ContinuumResult run(const std::filesystem::path& output_dir);

  // Solution access for tests: components u_0..u_{dim-1}, p (hydrodynamic), T at a point.
  dealii::Vector<double> value_at(const dealii::Point<dim>& point) const;
  unsigned long n_dofs() const { return dof_handler_.n_dofs(); }
  double thermodynamic_pressure() const { return P_; }

private:
  void setup_dofs();
  void make_constraints();
  void initial_guess();
  // P of the state x from the mass of the box: int n(P, T) dV = N (scalar Newton; one step for
  // the ideal gas). Sets P_.
  void update_thermodynamic_pressure(const dealii::Vector<double>& x);
  // At evaluation_point_ (P from its temperature first): residual (returns its norm) and, if
  // `with_jacobian`, the Jacobian at fixed P plus the rank-one coupling through P
  // (dR/dP and dP/dx).
  double assemble(bool with_jacobian, double gravity_factor);
  void solve_linear_system(); // Sherman-Morrison for the rank-one term
  bool newton(double gravity_factor, int& iterations);
  void solve_with_continuation();
  // Transient mode (end_time > 0): from rest at T_ref (walls at their temperatures) by implicit
  // Euler steps on the finest mesh, a Newton solve per step.
  void run_transient();
  void refine_mesh_and_transfer();
  void normalize_pressure();
  double volume_nusselt() const;
  void wall_nusselt(ContinuumResult& result) const;
  void consistent_wall_nusselt(ContinuumResult& result) const;
  void midline_maxima(ContinuumResult& result) const;
  void postprocess(ContinuumResult& result);
  void output_fields(const std::filesystem::path& dir, ContinuumResult& result) const;

  ContinuumParameters prm_;
  DimensionlessNumbers numbers_;
  double total_particles_ = 0;    // N = n_mean |Omega|
  double reference_pressure_ = 0; // p0 = n_mean k T_ref
  double reference_flux_ = 0;     // kappa(T_ref) dT / H (Le Quere 2005 Nu normalisation)
  double P_ = 0;                  // thermodynamic pressure
  double dn_dP_total_ = 0;        // int dn/dP dV at the last assembly
  dealii::Triangulation<dim> triangulation_;
  dealii::FESystem<dim> fe_;
  dealii::DoFHandler<dim> dof_handler_;
  dealii::AffineConstraints<double> nonzero_constraints_, zero_constraints_;
  dealii::SparsityPattern sparsity_pattern_;
  dealii::SparseMatrix<double> jacobian_;
  dealii::SparseDirectUMFPACK direct_solver_;
  dealii::Vector<double> solution_, evaluation_point_, newton_update_, residual_;
  dealii::Vector<double> residual_P_derivative_; // dR/dP (condensed)
  dealii::Vector<double> pressure_gradient_;     // dP/dx (raw, all DoFs)

  detail::LowMachTimeTerms time_terms_;
  dealii::Vector<double> old_solution_;
  double time_ = 0;
  int time_steps_ = 0;
  MeshLevel mesh_study_transient_; // the one mesh of a transient run

  PhaseTimes times_;
  int level_ = 0;
  int newton_iterations_ = 0;
  std::vector<double> continuation_rayleigh_;
};

} // namespace twinflow::continuum
