#pragma once
// Heat conduction without flow: n c_p dT/dt = div(kappa(T) grad T) + Q, steady (Newton with the
// exact Jacobian) or in time (theta scheme, Newton per step), Q2 elements, Dirichlet (fixed
// temperature), Neumann (prescribed flux) and periodic boundaries, volumetric heat slabs.
// Never builds a Navier-Stokes system. Instantiated for dim = 1, 2 (heat_conduction_1d2d.cpp)
// and 3 (heat_conduction_3d.cpp).

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_ilu.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <filesystem>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum {

template <int dim> class HeatConductionProblem {
public:
  explicit HeatConductionProblem(const ContinuumParameters& parameters);

  // The algorithm: mesh, setup, initial condition, then one steady Newton solve or the time
  // loop, postprocess; fields into `output_dir` unless it is empty.
  ContinuumResult run(const std::filesystem::path& output_dir);

  // For tests.
  double temperature_at(const dealii::Point<dim>& point) const;
  // max over quadrature points (Gauss, 4 per direction) of |T_h - T| / |T|
  double max_relative_error(const dealii::Function<dim>& exact) const;
  double integrate(const dealii::Function<dim>& weight) const; // int T w dV
  double time() const { return time_; }
  unsigned long n_dofs() const { return dof_handler_.n_dofs(); }

private:
  void make_mesh();
  void setup_system();
  void make_constraints(double pinned_temperature);
  void initial_condition();
  // Residual (and Jacobian) of the steady or theta-scheme equation at `evaluation_point_`.
  double assemble(bool with_jacobian);
  // One cell's share of them (assemble's loop): its values, its matrix and right-hand side.
  struct CellScratch {
    CellScratch(const dealii::FE_Q<dim>& fe, const dealii::Quadrature<dim>& quadrature);
    dealii::FEValues<dim> fe_values;
    dealii::FullMatrix<double> matrix;
    dealii::Vector<double> rhs;
    std::vector<double> T, T_old;
    std::vector<dealii::Tensor<1, dim>> grad_T, grad_T_old;
  };
  void assemble_cell(const typename dealii::DoFHandler<dim>::active_cell_iterator& cell,
                     bool with_jacobian, CellScratch& c) const;
  // Prescribed heat flux h into the domain through the cell's flux walls: - int_Gamma h phi.
  void add_wall_heat_flux(const typename dealii::DoFHandler<dim>::active_cell_iterator& cell,
                          dealii::FEFaceValues<dim>& fe_face_values,
                          dealii::Vector<double>& cell_rhs) const;
  void solve_linear_system(bool factorize);
  void newton(); // throws std::runtime_error if it does not converge
  void solve_steady();
  void time_loop();
  double mean_temperature(const dealii::Vector<double>&) const;
  void postprocess(ContinuumResult& result) const;
  void output_fields(const std::filesystem::path& dir, ContinuumResult& result) const;

  ContinuumParameters prm_;
  DimensionlessNumbers numbers_;
  bool has_fixed_temperature_ = false;
  bool linear_ = false; // constant kappa: the Jacobian never changes, factorize once
  bool factorized_ = false;
  bool transient_ = false;
  double time_ = 0, dt_ = 0;
  int steps_ = 0;
  int newton_iterations_ = 0;

  dealii::Triangulation<dim> triangulation_;
  dealii::FE_Q<dim> fe_;
  dealii::DoFHandler<dim> dof_handler_;
  dealii::AffineConstraints<double> nonzero_constraints_, zero_constraints_;
  dealii::SparsityPattern sparsity_pattern_;
  dealii::SparseMatrix<double> jacobian_;
  dealii::SparseDirectUMFPACK direct_solver_; // dim < 3
  dealii::SparseILU<double> ilu_;             // dim = 3: GMRES + ILU(0)
  dealii::Vector<double> solution_, old_solution_, evaluation_point_, newton_update_, residual_;
  PhaseTimes times_;
};

} // namespace twinflow::continuum
