#pragma once
// SerialBackend<dim>: included by the serial instantiation units (through
// flow_problem.templates.hpp) only.

#include <deal.II/dofs/dof_tools.h>

#include <algorithm>

#include "continuum/backend_serial.hpp"
#include "continuum/fields.templates.hpp"

namespace twinflow::continuum {

template <int dim> void SerialBackend<dim>::make_mesh() {
  detail::make_box_mesh(triangulation_, prm_);
}

template <int dim> void SerialBackend<dim>::refine(int times) {
  detail::refine_uniformly(triangulation_, prm_, times);
}

template <int dim> std::array<unsigned, 3> SerialBackend<dim>::cells() const {
  return detail::current_cells(triangulation_, prm_);
}

template <int dim>
void SerialBackend<dim>::refine_and_transfer(const dealii::DoFHandler<dim>& dofs, Vector& solution,
                                             const std::function<void()>& setup) {
  dealii::SolutionTransfer<dim> transfer(dofs);
  detail::flag_uniform_refinement(triangulation_, prm_);
  triangulation_.prepare_coarsening_and_refinement();
  const Vector coarse_solution = solution; // setup() resets the solution
  transfer.prepare_for_coarsening_and_refinement(coarse_solution);
  triangulation_.execute_coarsening_and_refinement();
  setup();
  Vector transferred(dofs.n_dofs());
  transfer.interpolate(coarse_solution, transferred);
  solution = transferred;
}

template <int dim>
void SerialBackend<dim>::distribute_dofs(dealii::DoFHandler<dim>& dofs,
                                         const dealii::FiniteElement<dim>& fe) {
  dofs.distribute_dofs(fe);
  n_dofs_ = dofs.n_dofs();
  is_velocity_.assign(n_dofs_, false);
  is_temperature_.assign(n_dofs_, false);
  for (const auto i : dealii::DoFTools::extract_dofs(
           dofs, fe.component_mask(dealii::FEValuesExtractors::Vector(0))))
    is_velocity_[i] = true;
  for (const auto i : dealii::DoFTools::extract_dofs(
           dofs, fe.component_mask(dealii::FEValuesExtractors::Scalar(dim + 1))))
    is_temperature_[i] = true;
}

template <int dim>
void SerialBackend<dim>::close_constraints(const dealii::DoFHandler<dim>& dofs, bool gauge_pressure,
                                           dealii::AffineConstraints<double>& c) const {
  detail::pin_free_translations(dofs, prm_, c);
  // Walls everywhere (or periodic): p is fixed only up to a constant; pin one value.
  if (gauge_pressure)
    for (const auto i : dealii::DoFTools::extract_dofs(
             dofs, dofs.get_fe().component_mask(dealii::FEValuesExtractors::Scalar(dim))))
      if (!c.is_constrained(i)) {
        c.add_line(i);
        break;
      }
  c.close();
}

template <int dim>
void SerialBackend<dim>::setup_matrix(const dealii::DoFHandler<dim>& dofs,
                                      const dealii::Table<2, dealii::DoFTools::Coupling>& coupling,
                                      const dealii::AffineConstraints<double>& zero_constraints) {
  dealii::DynamicSparsityPattern dsp(dofs.n_dofs());
  dealii::DoFTools::make_sparsity_pattern(dofs, coupling, dsp, zero_constraints, false);
  sparsity_pattern_.copy_from(dsp);
  jacobian_.reinit(sparsity_pattern_);
}

template <int dim>
unsigned SerialBackend<dim>::solve(const dealii::DoFHandler<dim>&, const Vector& residual,
                                   Vector& update,
                                   const dealii::AffineConstraints<double>& zero_constraints,
                                   const Vector* column, const Vector* row) {
  direct_solver_.initialize(jacobian_);
  direct_solver_.vmult(update, residual);
  zero_constraints.distribute(update);
  if (column) {
    Vector z2(column->size());
    direct_solver_.vmult(z2, *column);
    zero_constraints.distribute(z2);
    const double c_z1 = *row * update, c_z2 = *row * z2;
    update.add(-c_z1 / (1.0 + c_z2), z2);
  }
  return 0;
}

template <int dim>
std::array<double, 2> SerialBackend<dim>::velocity_temperature_norms(const Vector& v) const {
  double nu = 0, nt = 0;
  for (unsigned i = 0; i < v.size(); ++i) {
    if (is_velocity_[i]) nu += v[i] * v[i];
    if (is_temperature_[i]) nt += v[i] * v[i];
  }
  return {{std::sqrt(nu), std::sqrt(nt)}};
}

template <int dim>
void SerialBackend<dim>::subtract_from_component(const dealii::DoFHandler<dim>& dofs,
                                                 unsigned component, double value,
                                                 Vector& v) const {
  for (const auto i : dealii::DoFTools::extract_dofs(
           dofs, dofs.get_fe().component_mask(dealii::FEValuesExtractors::Scalar(component))))
    v[i] -= value;
}

template <int dim>
std::pair<double, double> SerialBackend<dim>::component_range(const dealii::DoFHandler<dim>& dofs,
                                                              unsigned component,
                                                              const Vector& v) const {
  double lo = 1e300, hi = -1e300;
  for (const auto i : dealii::DoFTools::extract_dofs(
           dofs, dofs.get_fe().component_mask(dealii::FEValuesExtractors::Scalar(component)))) {
    lo = std::min(lo, v[i]);
    hi = std::max(hi, v[i]);
  }
  return {lo, hi};
}

} // namespace twinflow::continuum
