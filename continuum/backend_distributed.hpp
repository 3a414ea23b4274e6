#pragma once
// The distributed backend of FlowProblem (flow_problem.hpp), for 3D boxes that a direct solver
// cannot factorise (step-32/55/57 style): p4est parallel::distributed::Triangulation (refined in
// every direction), DoFs in three blocks (velocity, s, temperature), Trilinos block matrices,
// each Newton system solved by FGMRES with a block-triangular preconditioner:
//   pressure: S ~ -(1/eta) M_p (ILU of the pressure mass matrix),
//   velocity: AMG of the velocity block, temperature: AMG of the temperature block;
// so for models whose scalar is a pressure (Boussinesq). Runs on one process or under mpirun.
// No pins: the Krylov solver tolerates the constant pressure mode.

#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "continuum/parameters.hpp"

namespace twinflow::continuum {

template <int dim> class DistributedBackend {
public:
  static constexpr bool distributed = true;
  using Triangulation = dealii::parallel::distributed::Triangulation<dim>;
  using Vector = dealii::TrilinosWrappers::MPI::BlockVector;        // owned
  using GhostedVector = dealii::TrilinosWrappers::MPI::BlockVector; // with ghosts
  using Matrix = dealii::TrilinosWrappers::BlockSparseMatrix;

  DistributedBackend(const ContinuumParameters& prm, MPI_Comm comm)
      : prm_(prm), comm_(comm), triangulation_(comm) {}

  MPI_Comm communicator() const { return comm_; }
  Triangulation& triangulation() { return triangulation_; }
  std::string where() const {
    return " on " + std::to_string(dealii::Utilities::MPI::n_mpi_processes(comm_)) + " processes";
  }

  void make_mesh();
  void refine(int times) { triangulation_.refine_global(times); }
  std::array<unsigned, 3> cells() const;
  void refine_and_transfer(const dealii::DoFHandler<dim>& dofs, Vector& solution,
                           const std::function<void()>& setup);

  void distribute_dofs(dealii::DoFHandler<dim>& dofs, const dealii::FiniteElement<dim>& fe);
  void clear_constraints(const dealii::DoFHandler<dim>& dofs,
                         dealii::AffineConstraints<double>& c) const;
  void close_constraints(const dealii::DoFHandler<dim>&, bool /*gauge_pressure*/,
                         dealii::AffineConstraints<double>& c) const {
    c.close();
  }
  // The Jacobian's pattern and the preconditioner's pressure mass matrix (its s-s block).
  void setup_matrix(const dealii::DoFHandler<dim>& dofs,
                    dealii::Table<2, dealii::DoFTools::Coupling> coupling,
                    const dealii::AffineConstraints<double>& zero_constraints);
  void reinit(Vector& v) const { v.reinit(owned_partitioning_, comm_); }
  void reinit_ghosted(GhostedVector& v) const {
    v.reinit(owned_partitioning_, relevant_partitioning_, comm_);
  }
  Matrix& matrix() { return jacobian_; }

  // FGMRES to 1e-8 of the residual; returns its iterations. No rank-one term.
  unsigned solve(const dealii::DoFHandler<dim>& dofs, const Vector& residual, Vector& update,
                 const dealii::AffineConstraints<double>& zero_constraints,
                 const Vector* column = nullptr, const Vector* row = nullptr);

  std::array<double, 2> velocity_temperature_norms(const Vector& v) const {
    return {{v.block(0).l2_norm(), v.block(2).l2_norm()}};
  }
  void subtract_from_component(const dealii::DoFHandler<dim>&, unsigned component, double value,
                               Vector& v) const {
    v.block(block_of(component)).add(-value);
  }
  std::pair<double, double> component_range(const dealii::DoFHandler<dim>&, unsigned component,
                                            const Vector& v) const;

private:
  static unsigned block_of(unsigned component) { return component < dim ? 0 : component - dim + 1; }
  void assemble_pressure_mass(const dealii::DoFHandler<dim>& dofs,
                              const dealii::AffineConstraints<double>& zero_constraints);

  const ContinuumParameters& prm_;
  MPI_Comm comm_;
  Triangulation triangulation_;
  std::vector<dealii::IndexSet> owned_partitioning_, relevant_partitioning_;
  Matrix jacobian_;
  Matrix preconditioner_matrix_; // (1,1): M_p / eta
  double first_residual_ = 0;    // scale of the absolute floor of the linear solves
};

} // namespace twinflow::continuum
