#pragma once
// The serial backend of FlowProblem (flow_problem.hpp): a deal.II Triangulation refined
// anisotropically where the box is a thin periodic slice, one sparse matrix, a direct solve
// (UMFPACK) with the Sherman-Morrison formula for a model's rank-one term. The linear algebra
// and mesh policy only; the algorithm is FlowProblem's (as step-40 separates its LA namespace).

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values_extractors.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/solution_transfer.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "continuum/parameters.hpp"

namespace twinflow::continuum {

template <int dim> class SerialBackend {
public:
  static constexpr bool distributed = false;
  using Triangulation = dealii::Triangulation<dim>;
  using Vector = dealii::Vector<double>;        // owned: solution, update, residual
  using GhostedVector = dealii::Vector<double>; // read by assembly and post-processing
  using Matrix = dealii::SparseMatrix<double>;

  SerialBackend(const ContinuumParameters& prm, MPI_Comm /*comm*/) : prm_(prm) {}

  MPI_Comm communicator() const { return MPI_COMM_SELF; }
  Triangulation& triangulation() { return triangulation_; }
  std::string where() const { return ""; } // for the progress lines

  void make_mesh();
  void refine(int times);
  std::array<unsigned, 3> cells() const;
  // Refines once (not along a thin slice) and carries `solution` over; `setup` distributes the
  // DoFs of the new mesh (and resizes `solution`).
  void refine_and_transfer(const dealii::DoFHandler<dim>& dofs, Vector& solution,
                           const std::function<void()>& setup);

  void distribute_dofs(dealii::DoFHandler<dim>& dofs, const dealii::FiniteElement<dim>& fe);
  void clear_constraints(const dealii::DoFHandler<dim>&,
                         dealii::AffineConstraints<double>& c) const {
    c.clear();
  }
  // The direct solver needs every null space pinned: free translations of the velocity and, if
  // the scalar is a gauge pressure, one pressure value.
  void close_constraints(const dealii::DoFHandler<dim>& dofs, bool gauge_pressure,
                         dealii::AffineConstraints<double>& c) const;
  void setup_matrix(const dealii::DoFHandler<dim>& dofs,
                    const dealii::Table<2, dealii::DoFTools::Coupling>& coupling,
                    const dealii::AffineConstraints<double>& zero_constraints);
  void reinit(Vector& v) const { v.reinit(n_dofs_); }
  void reinit_ghosted(GhostedVector& v) const { v.reinit(n_dofs_); }
  Matrix& matrix() { return jacobian_; }

  // Solves J update = residual, or (J + column row^T) update = residual with a rank-one term:
  // Sherman-Morrison (Golub & Van Loan, Matrix Computations, 4th ed., sec. 2.1.4) with one more
  // back-substitution, z1 = J^-1 r, z2 = J^-1 b, update = z1 - z2 (c . z1) / (1 + c . z2); c acts
  // on the distributed (full) vectors. Returns the linear iterations (0: direct).
  unsigned solve(const dealii::DoFHandler<dim>& dofs, const Vector& residual, Vector& update,
                 const dealii::AffineConstraints<double>& zero_constraints,
                 const Vector* column = nullptr, const Vector* row = nullptr);

  // |v| over the velocity and over the temperature DoFs.
  std::array<double, 2> velocity_temperature_norms(const Vector& v) const;
  void subtract_from_component(const dealii::DoFHandler<dim>& dofs, unsigned component,
                               double value, Vector& v) const;
  std::pair<double, double> component_range(const dealii::DoFHandler<dim>& dofs, unsigned component,
                                            const Vector& v) const;

private:
  const ContinuumParameters& prm_;
  Triangulation triangulation_;
  dealii::types::global_dof_index n_dofs_ = 0;
  std::vector<bool> is_velocity_, is_temperature_;
  dealii::SparsityPattern sparsity_pattern_;
  Matrix jacobian_;
  dealii::SparseDirectUMFPACK direct_solver_;
};

} // namespace twinflow::continuum
