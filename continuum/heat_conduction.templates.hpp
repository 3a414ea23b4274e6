#pragma once
// HeatConductionProblem<dim>: included by heat_conduction_1d2d.cpp and heat_conduction_3d.cpp.
//
// n c_p dT/dt = div(kappa(T) grad T) + Q (Fourier's law with a power-law conductivity), weak
// residual per step of the theta scheme (theta = 1/2: Crank-Nicolson, Hairer & Wanner II.7):
//   R(T) = int n c_p (T - T_old)/dt phi + theta a(T, phi) + (1 - theta) a(T_old, phi)
//   a(T, phi) = int kappa(T) grad T . grad phi - int Q phi - int_Gamma_N h phi
// and R(T) = a(T, phi) when steady; Newton's method with the exact Jacobian.

#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "continuum/fields.templates.hpp"
#include "continuum/heat_conduction.hpp"
#include "io/files.hpp"

namespace twinflow::continuum {

template <int dim>
HeatConductionProblem<dim>::HeatConductionProblem(const ContinuumParameters& parameters)
    : prm_(parameters), numbers_(dimensionless_numbers(parameters)), fe_(2),
      dof_handler_(triangulation_) {
  check(prm_);
  if (prm_.dim != dim) throw std::invalid_argument("HeatConductionProblem: dimension mismatch");
  for (int d = 0; d < dim; ++d)
    for (int side = 0; side < 2; ++side)
      has_fixed_temperature_ |=
          !prm_.boundary[d].periodic && prm_.boundary[d].fixed_temperature[side];
  linear_ = prm_.conductivity.is_constant();
  transient_ = prm_.transient();
  if (!transient_ && !has_fixed_temperature_) {
    // Steady state without a fixed temperature exists only if no net heat enters.
    double power = 0, scale = 0;
    for (const auto& s : prm_.heat_slabs) power += s.power, scale += std::abs(s.power);
    for (int d = 0; d < dim; ++d) {
      double area = 1;
      for (int e = 0; e < dim; ++e)
        if (e != d) area *= prm_.box[e];
      if (!prm_.boundary[d].periodic)
        for (int side = 0; side < 2; ++side)
          power += prm_.boundary[d].heat_flux[side] * area,
              scale += std::abs(prm_.boundary[d].heat_flux[side] * area);
    }
    if (std::abs(power) > 1e-12 * scale)
      throw std::invalid_argument(
          "continuum parameters: a steady state without fixed-temperature walls needs zero net "
          "heat input (sources + wall fluxes)");
  }
}

template <int dim>
ContinuumResult HeatConductionProblem<dim>::run(const std::filesystem::path& out) {
  ContinuumResult result;
  result.model = "heat-conduction";
  result.dim = dim;
  result.numbers = numbers_;
  {
    detail::ScopedTimer timer(times_.setup);
    make_mesh();
    setup_system();
    initial_condition();
  }
  if (transient_)
    time_loop();
  else
    solve_steady();
  {
    detail::ScopedTimer timer(times_.postprocess);
    postprocess(result);
  }
  if (!out.empty()) {
    detail::ScopedTimer timer(times_.output);
    output_fields(out, result);
  }
  result.times = times_;
  return result;
}

template <int dim> void HeatConductionProblem<dim>::make_mesh() {
  detail::make_box_mesh(triangulation_, prm_);
  detail::refine_uniformly(triangulation_, prm_, prm_.refinements);
}

template <int dim> void HeatConductionProblem<dim>::make_constraints(double pinned_temperature) {
  for (const bool homogeneous : {false, true}) {
    auto& c = homogeneous ? zero_constraints_ : nonzero_constraints_;
    c.clear();
    detail::add_periodicity(dof_handler_, prm_, c);
    for (int d = 0; d < dim; ++d)
      for (int side = 0; side < 2; ++side)
        if (!prm_.boundary[d].periodic && prm_.boundary[d].fixed_temperature[side])
          dealii::VectorTools::interpolate_boundary_values(
              dof_handler_, 2 * d + side,
              dealii::Functions::ConstantFunction<dim>(
                  homogeneous ? 0.0 : prm_.boundary[d].temperature[side]),
              c);
    // Steady without fixed temperatures: T is known up to a constant; pin one value (the
    // mean is restored by solve_steady).
    if (!transient_ && !has_fixed_temperature_)
      for (unsigned i = 0; i < dof_handler_.n_dofs(); ++i)
        if (!c.is_constrained(i)) {
          c.add_line(i);
          c.set_inhomogeneity(i, homogeneous ? 0.0 : pinned_temperature);
          break;
        }
    c.close();
  }
}

template <int dim> void HeatConductionProblem<dim>::setup_system() {
  dof_handler_.distribute_dofs(fe_);
  make_constraints(prm_.reference_temperature);
  dealii::DynamicSparsityPattern dsp(dof_handler_.n_dofs());
  dealii::DoFTools::make_sparsity_pattern(dof_handler_, dsp, zero_constraints_, false);
  sparsity_pattern_.copy_from(dsp);
  jacobian_.reinit(sparsity_pattern_);
  for (auto* v : {&solution_, &old_solution_, &evaluation_point_, &newton_update_, &residual_})
    v->reinit(dof_handler_.n_dofs());
}

template <int dim> void HeatConductionProblem<dim>::initial_condition() {
  if (prm_.initial_temperature.empty()) {
    solution_ = prm_.reference_temperature;
  } else {
    dealii::VectorTools::interpolate(dof_handler_,
                                     *detail::initial_temperature_expression<dim>(prm_), solution_);
  }
  nonzero_constraints_.distribute(solution_);
  old_solution_ = solution_;
}

template <int dim>
void HeatConductionProblem<dim>::add_wall_heat_flux(
    const typename dealii::DoFHandler<dim>::active_cell_iterator& cell,
    dealii::FEFaceValues<dim>& fe_face_values, dealii::Vector<double>& cell_rhs) const {
  const unsigned n = fe_.n_dofs_per_cell(), nq = fe_face_values.n_quadrature_points;
  for (const auto& face : cell->face_iterators()) {
    if (!face->at_boundary()) continue;
    const int d = face->boundary_id() / 2, side = face->boundary_id() % 2;
    const auto& b = prm_.boundary[d];
    if (b.periodic || b.fixed_temperature[side] || b.heat_flux[side] == 0.0) continue;
    fe_face_values.reinit(cell, face);
    for (unsigned q = 0; q < nq; ++q)
      for (unsigned i = 0; i < n; ++i)
        cell_rhs(i) += b.heat_flux[side] * fe_face_values.shape_value(i, q) * fe_face_values.JxW(q);
  }
}

template <int dim>
HeatConductionProblem<dim>::CellScratch::CellScratch(const dealii::FE_Q<dim>& fe,
                                                     const dealii::Quadrature<dim>& quadrature)
    : fe_values(fe, quadrature,
                dealii::update_values | dealii::update_gradients |
                    dealii::update_quadrature_points | dealii::update_JxW_values),
      matrix(fe.n_dofs_per_cell(), fe.n_dofs_per_cell()), rhs(fe.n_dofs_per_cell()),
      T(quadrature.size()), T_old(quadrature.size()), grad_T(quadrature.size()),
      grad_T_old(quadrature.size()) {}

template <int dim> double HeatConductionProblem<dim>::assemble(bool with_jacobian) {
  detail::ScopedTimer timer(times_.assembly);
  if (with_jacobian) jacobian_ = 0;
  residual_ = 0;
  CellScratch c(fe_, dealii::QGauss<dim>(3));
  dealii::FEFaceValues<dim> fe_face_values(fe_, dealii::QGauss<dim - 1>(3),
                                           dealii::update_values | dealii::update_JxW_values);
  std::vector<dealii::types::global_dof_index> dofs(fe_.n_dofs_per_cell());
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    assemble_cell(cell, with_jacobian, c);
    add_wall_heat_flux(cell, fe_face_values, c.rhs);
    cell->get_dof_indices(dofs);
    if (with_jacobian)
      zero_constraints_.distribute_local_to_global(c.matrix, c.rhs, dofs, jacobian_, residual_);
    else
      zero_constraints_.distribute_local_to_global(c.rhs, dofs, residual_);
  }
  return residual_.l2_norm();
}

template <int dim>
void HeatConductionProblem<dim>::assemble_cell(
    const typename dealii::DoFHandler<dim>::active_cell_iterator& cell, bool with_jacobian,
    CellScratch& c) const {
  auto& fe_values = c.fe_values;
  const unsigned n = fe_.n_dofs_per_cell(), nq = c.T.size();
  const double T_ref = prm_.reference_temperature, ncp = prm_.heat_capacity_per_volume();
  // Steady: only the implicit part, with weight 1.
  const double theta = transient_ ? prm_.theta : 1.0;
  const double mass = transient_ ? ncp / dt_ : 0.0;
  fe_values.reinit(cell);
  c.matrix = 0;
  c.rhs = 0;
  fe_values.get_function_values(evaluation_point_, c.T);
  fe_values.get_function_gradients(evaluation_point_, c.grad_T);
  if (transient_) {
    fe_values.get_function_values(old_solution_, c.T_old);
    fe_values.get_function_gradients(old_solution_, c.grad_T_old);
  }
  for (unsigned q = 0; q < nq; ++q) {
    const double kappa = prm_.conductivity.at(c.T[q], T_ref);
    const double dkappa = prm_.conductivity.derivative(c.T[q], T_ref);
    const double kappa_old = transient_ ? prm_.conductivity.at(c.T_old[q], T_ref) : 0.0;
    const auto x = fe_values.quadrature_point(q);
    std::array<double, 3> x3{{0, 0, 0}};
    for (int d = 0; d < dim; ++d) x3[d] = x[d];
    const double source = heat_source_density(prm_, x3);
    const double JxW = fe_values.JxW(q);
    // Flux terms of the theta scheme: theta kappa grad T + (1 - theta) kappa_old grad T_old.
    dealii::Tensor<1, dim> flux = theta * kappa * c.grad_T[q];
    if (transient_) flux += (1 - theta) * kappa_old * c.grad_T_old[q];
    const double storage = transient_ ? mass * (c.T[q] - c.T_old[q]) : 0.0;
    for (unsigned i = 0; i < n; ++i) {
      const double phi_i = fe_values.shape_value(i, q);
      const auto grad_phi_i = fe_values.shape_grad(i, q);
      c.rhs(i) -= (storage * phi_i + flux * grad_phi_i - source * phi_i) * JxW;
      if (!with_jacobian) continue;
      for (unsigned j = 0; j < n; ++j)
        c.matrix(i, j) +=
            (mass * fe_values.shape_value(j, q) * phi_i +
             theta * (kappa * (fe_values.shape_grad(j, q) * grad_phi_i) +
                      dkappa * fe_values.shape_value(j, q) * (c.grad_T[q] * grad_phi_i))) *
            JxW;
    }
  }
}

template <int dim> void HeatConductionProblem<dim>::solve_linear_system(bool factorize) {
  detail::ScopedTimer timer(times_.solve);
  if constexpr (dim < 3) {
    if (factorize) direct_solver_.initialize(jacobian_);
    direct_solver_.vmult(newton_update_, residual_);
  } else {
    // 3D: UMFPACK's fill-in makes one factorisation of 18k Q2 unknowns take ~7 s here; GMRES
    // with ILU(0) takes well under a second. Tolerance 1e-12 of the residual, far below the
    // discretisation error.
    if (factorize) ilu_.initialize(jacobian_);
    dealii::SolverControl control(2000, 1e-12 * residual_.l2_norm());
    dealii::SolverGMRES<dealii::Vector<double>> gmres(
        control, typename dealii::SolverGMRES<dealii::Vector<double>>::AdditionalData(100));
    newton_update_ = 0;
    gmres.solve(jacobian_, newton_update_, residual_, ilu_);
  }
  zero_constraints_.distribute(newton_update_);
}

template <int dim> void HeatConductionProblem<dim>::newton() {
  // Constant kappa: the equation is linear, one Newton step solves it (to round-off) and the
  // Jacobian is the same every step. Otherwise iterate to a relative update below tolerance.
  evaluation_point_ = solution_;
  for (int it = 0; it < prm_.max_newton_iterations; ++it) {
    const bool refactorize = !linear_ || !factorized_;
    assemble(refactorize);
    solve_linear_system(refactorize);
    factorized_ = true;
    solution_ = evaluation_point_;
    solution_ += newton_update_;
    evaluation_point_ = solution_;
    ++newton_iterations_;
    if (linear_ || newton_update_.l2_norm() <= prm_.newton_tolerance * solution_.l2_norm()) return;
  }
  throw std::runtime_error("heat conduction: Newton did not converge in " +
                           std::to_string(prm_.max_newton_iterations) + " iterations");
}

template <int dim> void HeatConductionProblem<dim>::solve_steady() {
  if (has_fixed_temperature_) {
    newton();
    return;
  }
  // Pinned value adjusted by the secant method until the mean equals the initial mean (energy
  // of a closed box); with constant kappa the first shift is exact.
  const double target = mean_temperature(solution_);
  double pinned = target, previous_pinned = 0, previous_miss = 0;
  for (int k = 0; k < 30; ++k) {
    make_constraints(pinned);
    nonzero_constraints_.distribute(solution_);
    newton();
    const double miss = mean_temperature(solution_) - target;
    if (std::abs(miss) <= 1e-12 * std::abs(target)) return;
    const double next = k == 0 || miss == previous_miss
                            ? pinned - miss
                            : pinned - miss * (pinned - previous_pinned) / (miss - previous_miss);
    solution_.add(next - pinned); // the shifted solution: a close initial guess
    previous_pinned = pinned, previous_miss = miss, pinned = next;
  }
  throw std::runtime_error("heat conduction: the mean temperature did not settle");
}

template <int dim> void HeatConductionProblem<dim>::time_loop() {
  steps_ = std::max(1, static_cast<int>(std::lround(prm_.end_time / prm_.time_step)));
  dt_ = prm_.end_time / steps_;
  for (int step = 0; step < steps_; ++step) {
    old_solution_ = solution_;
    newton();
    time_ = (step + 1) * dt_;
  }
}

template <int dim>
double HeatConductionProblem<dim>::mean_temperature(const dealii::Vector<double>& v) const {
  return dealii::VectorTools::compute_mean_value(dof_handler_, dealii::QGauss<dim>(3), v, 0);
}

template <int dim> void HeatConductionProblem<dim>::postprocess(ContinuumResult& result) const {
  result.dofs = dof_handler_.n_dofs();
  result.cells = detail::current_cells(triangulation_, prm_);
  result.newton_iterations = newton_iterations_;
  result.time = time_;
  result.time_steps = steps_;
  result.temperature_min = *std::min_element(solution_.begin(), solution_.end());
  result.temperature_max = *std::max_element(solution_.begin(), solution_.end());
  result.temperature_mean = mean_temperature(solution_);
  // Heat into the domain through the two walls of the heated (else the first walled) direction:
  // int kappa grad T . n (n outward).
  int d = numbers_.heated_direction;
  for (int e = 0; e < dim && d < 0; ++e)
    if (!prm_.boundary[e].periodic) d = e;
  if (d >= 0) {
    const dealii::QGauss<dim - 1> face_quadrature(3);
    dealii::FEFaceValues<dim> fe_face_values(fe_, face_quadrature,
                                             dealii::update_values | dealii::update_gradients |
                                                 dealii::update_normal_vectors |
                                                 dealii::update_JxW_values);
    std::vector<double> T(face_quadrature.size());
    std::vector<dealii::Tensor<1, dim>> grad_T(face_quadrature.size());
    for (const auto& cell : dof_handler_.active_cell_iterators())
      for (const auto& face : cell->face_iterators()) {
        if (!face->at_boundary() || face->boundary_id() / 2 != static_cast<unsigned>(d)) continue;
        fe_face_values.reinit(cell, face);
        fe_face_values.get_function_values(solution_, T);
        fe_face_values.get_function_gradients(solution_, grad_T);
        double& into = face->boundary_id() % 2 ? result.heat_flux_upper : result.heat_flux_lower;
        for (unsigned q = 0; q < face_quadrature.size(); ++q)
          into += prm_.conductivity.at(T[q], prm_.reference_temperature) *
                  (grad_T[q] * fe_face_values.normal_vector(q)) * fe_face_values.JxW(q);
      }
  }
  result.bins = detail::bin_averages(dof_handler_, solution_, {"T"}, prm_);
  detail::probe(dof_handler_, solution_, prm_, result);
}

template <int dim>
void HeatConductionProblem<dim>::output_fields(const std::filesystem::path& dir,
                                               ContinuumResult& result) const {
  if (!prm_.write_fields) return;
  if constexpr (dim == 1) {
    // deal.II 9.4 writes no HDF5/XDMF for 1D meshes: the profile at the nodes as CSV instead.
    std::map<dealii::types::global_dof_index, dealii::Point<dim>> support;
    dealii::DoFTools::map_dofs_to_support_points(dealii::MappingQ1<dim>(), dof_handler_, support);
    std::vector<std::pair<double, double>> profile;
    for (const auto& [dof, x] : support) profile.emplace_back(x[0], solution_[dof]);
    std::sort(profile.begin(), profile.end());
    std::ostringstream csv;
    csv << std::setprecision(15) << "x,T\n";
    for (const auto& [x, T] : profile) csv << x << "," << T << "\n";
    io::write_file_atomically(dir / "fields.csv", csv.str());
    result.files.push_back("fields.csv");
    return;
  }
  dealii::DataOut<dim> data_out;
  data_out.attach_dof_handler(dof_handler_);
  data_out.add_data_vector(solution_, "T");
  data_out.build_patches(2);
  detail::write_hdf5_xdmf(data_out, dir, time_, result.files);
}

template <int dim>
double HeatConductionProblem<dim>::temperature_at(const dealii::Point<dim>& point) const {
  return dealii::VectorTools::point_value(dof_handler_, solution_, point);
}

template <int dim>
double HeatConductionProblem<dim>::max_relative_error(const dealii::Function<dim>& exact) const {
  const dealii::QGauss<dim> quadrature(4);
  dealii::FEValues<dim> fe_values(fe_, quadrature,
                                  dealii::update_values | dealii::update_quadrature_points);
  std::vector<double> T(quadrature.size());
  double error = 0;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    fe_values.reinit(cell);
    fe_values.get_function_values(solution_, T);
    for (unsigned q = 0; q < quadrature.size(); ++q) {
      const double t = exact.value(fe_values.quadrature_point(q));
      error = std::max(error, std::abs(T[q] - t) / std::abs(t));
    }
  }
  return error;
}

template <int dim>
double HeatConductionProblem<dim>::integrate(const dealii::Function<dim>& weight) const {
  const dealii::QGauss<dim> quadrature(4);
  dealii::FEValues<dim> fe_values(fe_, quadrature,
                                  dealii::update_values | dealii::update_quadrature_points |
                                      dealii::update_JxW_values);
  std::vector<double> T(quadrature.size());
  double integral = 0;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    fe_values.reinit(cell);
    fe_values.get_function_values(solution_, T);
    for (unsigned q = 0; q < quadrature.size(); ++q)
      integral += T[q] * weight.value(fe_values.quadrature_point(q)) * fe_values.JxW(q);
  }
  return integral;
}

} // namespace twinflow::continuum
