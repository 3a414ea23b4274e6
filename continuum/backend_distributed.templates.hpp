#pragma once
// DistributedBackend<dim>: included by the distributed instantiation unit (through
// flow_problem.templates.hpp) only. Solver structure: step-32 / step-55 (block-triangular
// preconditioner, AMG per block).

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/block_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <algorithm>

#include "continuum/backend_distributed.hpp"
#include "continuum/fields.templates.hpp"

namespace twinflow::continuum {

namespace detail {
using BlockVector = dealii::TrilinosWrappers::MPI::BlockVector;

// Upper block-triangular preconditioner of [A B^T C; B 0 0; D 0 E] (velocity, pressure,
// temperature; Elman, Silvester & Wathen 2014, ch. 9): z_p = -eta M_p^{-1} r_p (Schur complement
// -B A^{-1} B^T ~ -M_p / eta), z_u = A^{-1}(r_u - B^T z_p), z_T = E^{-1}(r_T - D z_u), with one
// AMG V-cycle for A^{-1} and E^{-1} and ILU for M_p^{-1}.
class BlockTriangularPreconditioner {
public:
  BlockTriangularPreconditioner(const dealii::TrilinosWrappers::BlockSparseMatrix& jacobian,
                                const dealii::TrilinosWrappers::PreconditionAMG& velocity,
                                const dealii::TrilinosWrappers::PreconditionILU& pressure_mass,
                                const dealii::TrilinosWrappers::PreconditionAMG& temperature,
                                double eta)
      : jacobian_(jacobian), velocity_(velocity), pressure_mass_(pressure_mass),
        temperature_(temperature), eta_(eta) {}

  void vmult(BlockVector& dst, const BlockVector& src) const {
    pressure_mass_.vmult(dst.block(1), src.block(1));
    dst.block(1) *= -eta_;
    tmp_u_.reinit(src.block(0), true);
    jacobian_.block(0, 1).vmult(tmp_u_, dst.block(1));
    tmp_u_.sadd(-1.0, src.block(0));
    velocity_.vmult(dst.block(0), tmp_u_);
    tmp_T_.reinit(src.block(2), true);
    jacobian_.block(2, 0).vmult(tmp_T_, dst.block(0));
    tmp_T_.sadd(-1.0, src.block(2));
    temperature_.vmult(dst.block(2), tmp_T_);
  }

private:
  const dealii::TrilinosWrappers::BlockSparseMatrix& jacobian_;
  const dealii::TrilinosWrappers::PreconditionAMG& velocity_;
  const dealii::TrilinosWrappers::PreconditionILU& pressure_mass_;
  const dealii::TrilinosWrappers::PreconditionAMG& temperature_;
  const double eta_;
  mutable dealii::TrilinosWrappers::MPI::Vector tmp_u_, tmp_T_;
};

// AMG for an elliptic block of Q2 unknowns (component mask `mask`).
template <int dim>
void initialize_amg(dealii::TrilinosWrappers::PreconditionAMG& amg,
                    const dealii::TrilinosWrappers::SparseMatrix& block,
                    const dealii::DoFHandler<dim>& dofs, const dealii::ComponentMask& mask) {
  dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
  dealii::DoFTools::extract_constant_modes(dofs, mask, data.constant_modes);
  data.elliptic = true;
  data.higher_order_elements = true;
  data.smoother_sweeps = 2;
  data.aggregation_threshold = 0.02;
  amg.initialize(block, data);
}
} // namespace detail

template <int dim> void DistributedBackend<dim>::make_mesh() {
  detail::make_box_mesh(triangulation_, prm_);
  std::vector<dealii::GridTools::PeriodicFacePair<typename Triangulation::cell_iterator>> pairs;
  for (int d = 0; d < dim; ++d)
    if (prm_.boundary[d].periodic)
      dealii::GridTools::collect_periodic_faces(triangulation_, 2 * d, 2 * d + 1, d, pairs);
  if (!pairs.empty()) triangulation_.add_periodicity(pairs);
}

template <int dim> std::array<unsigned, 3> DistributedBackend<dim>::cells() const {
  std::array<unsigned, 3> cells{{0, 0, 0}};
  for (int d = 0; d < dim; ++d) cells[d] = prm_.cells[d] << (triangulation_.n_global_levels() - 1);
  return cells;
}

template <int dim>
void DistributedBackend<dim>::refine_and_transfer(const dealii::DoFHandler<dim>& dofs,
                                                  Vector& solution,
                                                  const std::function<void()>& setup) {
  dealii::parallel::distributed::SolutionTransfer<dim, Vector> transfer(dofs);
  GhostedVector ghosted;
  reinit_ghosted(ghosted);
  ghosted = solution;
  triangulation_.set_all_refine_flags();
  triangulation_.prepare_coarsening_and_refinement();
  transfer.prepare_for_coarsening_and_refinement(ghosted);
  triangulation_.execute_coarsening_and_refinement();
  setup();
  transfer.interpolate(solution);
}

template <int dim>
void DistributedBackend<dim>::distribute_dofs(dealii::DoFHandler<dim>& dofs,
                                              const dealii::FiniteElement<dim>& fe) {
  dofs.distribute_dofs(fe);
  // Blocks: velocity, s, temperature.
  std::vector<unsigned> block_component(dim + 2, 0);
  block_component[dim] = 1;
  block_component[dim + 1] = 2;
  dealii::DoFRenumbering::component_wise(dofs, block_component);
  const auto per_block = dealii::DoFTools::count_dofs_per_fe_block(dofs, block_component);
  const dealii::IndexSet owned = dofs.locally_owned_dofs();
  const dealii::IndexSet relevant = dealii::DoFTools::extract_locally_relevant_dofs(dofs);
  owned_partitioning_.clear();
  relevant_partitioning_.clear();
  dealii::types::global_dof_index begin = 0;
  for (unsigned b = 0; b < 3; ++b) {
    owned_partitioning_.push_back(owned.get_view(begin, begin + per_block[b]));
    relevant_partitioning_.push_back(relevant.get_view(begin, begin + per_block[b]));
    begin += per_block[b];
  }
}

template <int dim>
void DistributedBackend<dim>::clear_constraints(const dealii::DoFHandler<dim>& dofs,
                                                dealii::AffineConstraints<double>& c) const {
  c.clear();
  c.reinit(dealii::DoFTools::extract_locally_relevant_dofs(dofs));
}

template <int dim>
void DistributedBackend<dim>::setup_matrix(
    const dealii::DoFHandler<dim>& dofs, dealii::Table<2, dealii::DoFTools::Coupling> coupling,
    const dealii::AffineConstraints<double>& zero_constraints) {
  coupling[dim][dim] = dealii::DoFTools::always; // the pressure mass matrix
  const dealii::IndexSet owned = dofs.locally_owned_dofs();
  const dealii::IndexSet relevant = dealii::DoFTools::extract_locally_relevant_dofs(dofs);
  dealii::BlockDynamicSparsityPattern dsp(relevant_partitioning_);
  dealii::DoFTools::make_sparsity_pattern(dofs, coupling, dsp, zero_constraints, false,
                                          dealii::Utilities::MPI::this_mpi_process(comm_));
  dealii::SparsityTools::distribute_sparsity_pattern(dsp, owned, comm_, relevant);
  jacobian_.reinit(owned_partitioning_, dsp, comm_);
  preconditioner_matrix_.reinit(owned_partitioning_, dsp, comm_);
  assemble_pressure_mass(dofs, zero_constraints);
}

template <int dim>
void DistributedBackend<dim>::assemble_pressure_mass(
    const dealii::DoFHandler<dim>& dofs,
    const dealii::AffineConstraints<double>& zero_constraints) {
  // (1/eta_ref) M_p, the Schur-complement approximation (Elman, Silvester & Wathen 2014, ch. 9).
  preconditioner_matrix_ = 0;
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(dofs.get_fe(), quadrature,
                                  dealii::update_values | dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Scalar pressure(dim);
  const unsigned n = dofs.get_fe().n_dofs_per_cell();
  dealii::FullMatrix<double> cell_matrix(n, n);
  std::vector<dealii::types::global_dof_index> dof_indices(n);
  const double eta = prm_.viscosity.at(prm_.reference_temperature, prm_.reference_temperature);
  for (const auto& cell : dofs.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    cell_matrix = 0;
    for (unsigned q = 0; q < quadrature.size(); ++q)
      for (unsigned i = 0; i < n; ++i)
        for (unsigned j = 0; j < n; ++j)
          cell_matrix(i, j) += fe_values[pressure].value(i, q) * fe_values[pressure].value(j, q) /
                               eta * fe_values.JxW(q);
    cell->get_dof_indices(dof_indices);
    zero_constraints.distribute_local_to_global(cell_matrix, dof_indices, preconditioner_matrix_);
  }
  preconditioner_matrix_.compress(dealii::VectorOperation::add);
}

template <int dim>
unsigned DistributedBackend<dim>::solve(const dealii::DoFHandler<dim>& dofs, const Vector& residual,
                                        Vector& update,
                                        const dealii::AffineConstraints<double>& zero_constraints,
                                        const Vector* column, const Vector*) {
  if (column) throw std::logic_error("the distributed backend has no rank-one term");
  const auto& fe = dofs.get_fe();
  dealii::TrilinosWrappers::PreconditionAMG velocity_amg, temperature_amg;
  detail::initialize_amg(velocity_amg, jacobian_.block(0, 0), dofs,
                         fe.component_mask(dealii::FEValuesExtractors::Vector(0)));
  detail::initialize_amg(temperature_amg, jacobian_.block(2, 2), dofs,
                         fe.component_mask(dealii::FEValuesExtractors::Scalar(dim + 1)));
  dealii::TrilinosWrappers::PreconditionILU pressure_ilu;
  pressure_ilu.initialize(preconditioner_matrix_.block(1, 1));
  const detail::BlockTriangularPreconditioner preconditioner(
      jacobian_, velocity_amg, pressure_ilu, temperature_amg,
      prm_.viscosity.at(prm_.reference_temperature, prm_.reference_temperature));
  // Inexact Newton: 1e-8 of the residual keeps the outer convergence (near) quadratic down to
  // the Newton tolerance; the floor (1e-14 of the first residual) stops the last iterations
  // from chasing round-off. Not reaching it is left to Newton's own convergence test.
  const double norm = residual.l2_norm();
  if (first_residual_ == 0) first_residual_ = norm;
  dealii::SolverControl control(1000, std::max(1e-8 * norm, 1e-14 * first_residual_));
  dealii::SolverFGMRES<Vector> solver(control,
                                      typename dealii::SolverFGMRES<Vector>::AdditionalData(100));
  update = 0;
  try {
    solver.solve(jacobian_, update, residual, preconditioner);
  } catch (const dealii::SolverControl::NoConvergence&) {
  }
  zero_constraints.distribute(update);
  return control.last_step();
}

template <int dim>
std::pair<double, double> DistributedBackend<dim>::component_range(const dealii::DoFHandler<dim>&,
                                                                   unsigned component,
                                                                   const Vector& v) const {
  const auto& block = v.block(block_of(component));
  double lo = 1e300, hi = -1e300;
  for (const auto i : block.locally_owned_elements()) {
    lo = std::min(lo, block[i]);
    hi = std::max(hi, block[i]);
  }
  return {dealii::Utilities::MPI::min(lo, comm_), dealii::Utilities::MPI::max(hi, comm_)};
}

} // namespace twinflow::continuum
