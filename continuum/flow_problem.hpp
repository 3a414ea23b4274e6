#pragma once
// Natural convection by Newton's method, one solver for every flow model and backend (deal.II
// step-31/57 for the equations and Newton, step-40 for separating serial and distributed linear
// algebra). Unknowns (u, s, T) on Taylor-Hood Q2/Q1 velocity/scalar with Q2 temperature; the
// model (flow_model.hpp: Boussinesq, low-Mach) gives the cell residual and its exact Jacobian and
// the initial state; the backend (backend_serial.hpp: direct UMFPACK; backend_distributed.hpp:
// p4est + Trilinos FGMRES) the mesh policy and the linear solves. Steady: nested iteration over
// the refinement levels with continuation in Ra on the first (a mesh study); in time: BDF2 (or
// the model's implicit Euler) on the finest mesh, one Newton solve per step. Setting the
// environment variable TWINFLOW_NEWTON_DEBUG prints every Newton iteration.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <vector>

#include "continuum/flow_model.hpp"
#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum {

template <int dim, class Model, class Backend> class FlowProblem {
public:
  explicit FlowProblem(const ContinuumParameters& parameters, MPI_Comm comm = MPI_COMM_WORLD);

  // The algorithm: mesh; steady: per refinement level setup, Newton (with continuation in Ra
  // on the first level); in time: march on the finest mesh; postprocess; fields into
  // `output_dir` unless it is empty (in time: snapshots as a series).
  ContinuumResult run(const std::filesystem::path& output_dir);

  // For tests (serial backend): components u_0..u_{dim-1}, s, T at a point.
  dealii::Vector<double> value_at(const dealii::Point<dim>& point) const;
  // For tests (serial backend): L2 norms over the box of u - u_exact, s - s_exact, T - T_exact,
  // `exact` with the dim + 2 components.
  std::array<double, 3> l2_errors(const dealii::Function<dim>& exact) const;
  // The same norms of this solution less `other`'s on the same mesh (a time-step study).
  std::array<double, 3> l2_difference(const FlowProblem& other) const;
  unsigned long n_dofs() const { return dof_handler_.n_dofs(); }
  const Model& model() const { return model_; }
  Model& model() { return model_; } // for tests: a manufactured solution's forcing

private:
  using Vector = typename Backend::Vector;
  std::array<double, 3> l2_norms(const Vector& x, const dealii::Function<dim>& exact) const;
  using GhostedVector = typename Backend::GhostedVector;

  void setup_dofs();
  void make_constraints();
  void initial_guess(); // the model's initial state, then its derived state
  // Steady: nested iteration, one MeshLevel per refinement level.
  void solve_on_each_level(ContinuumResult& result);
  MeshLevel finish_level(int level, std::chrono::steady_clock::time_point start,
                         int iterations_before, double previous_nusselt);
  // In time: from the initial state to the end time; time series and field snapshots.
  void march_in_time(const std::filesystem::path& dir, ContinuumResult& result);
  // One step to `time` with the BDF coefficients `bdf`: the history from x^n and x^{n-1}
  // (`previous`, moved on), one Newton solve from the last state; its Newton iterations.
  int step_in_time(int step, double time, const std::array<double, 3>& bdf, Vector& previous);
  // Residual (always) and Jacobian (if `with_jacobian`) at `evaluation_point_` for gravity
  // scaled by `gravity_factor`, with the time derivatives of the current step when in time;
  // returns the residual norm.
  double assemble(bool with_jacobian, double gravity_factor);
  // Newton iterations at one gravity factor; false if they did not converge.
  bool newton(double gravity_factor, int& iterations);
  // Reaches the full gravity in steps of the Rayleigh number (10x; halved on failure).
  void solve_with_continuation();
  void refine_mesh_and_transfer();
  // Zero-mean pressure (a gauge pressure's constant is free); then the ghosted copy.
  void normalize_pressure();
  FlowIntegrals integrals() const; // of evaluation_point_
  TimeSample sample(int step, int newton_iterations) const;
  void postprocess(ContinuumResult& result);
  // Builds the output of the state (the model's derived fields included) and hands it to
  // `write` (one field file, or a snapshot of a series).
  void write_fields(const std::function<void(const dealii::DataOut<dim>&)>& write) const;
  void output_fields(const std::filesystem::path& dir, ContinuumResult& result) const;

  ContinuumParameters prm_;
  DimensionlessNumbers numbers_;
  Backend backend_; // mesh, matrix and linear solver
  dealii::FESystem<dim> fe_;
  dealii::DoFHandler<dim> dof_handler_;
  Model model_;
  dealii::ConditionalOStream pcout_;                      // the first process prints
  dealii::AffineConstraints<double> nonzero_constraints_; // boundary values of the solution
  dealii::AffineConstraints<double> zero_constraints_;    // the same, homogeneous: updates

  Vector solution_, newton_update_, residual_;
  GhostedVector evaluation_point_;        // the state assembled and post-processed
  Vector rank_one_column_, rank_one_row_; // models with a global scalar (CellSystem)
  // In time: the BDF coefficients of the step (time_schedule.hpp; all 0 when steady), the
  // history c1 x^n + c2 x^{n-1}, x^n and x^{n-1} (AssemblyContext).
  std::array<double, 3> bdf_{{0, 0, 0}};
  double dt_ = 0;
  GhostedVector history_, previous_, older_;

  PhaseTimes times_;
  int newton_iterations_ = 0;
  std::vector<double> continuation_rayleigh_;
};

} // namespace twinflow::continuum
