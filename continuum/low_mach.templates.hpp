#pragma once
// LowMachProblem<dim>: included by low_mach_2d.cpp and low_mach_3d.cpp only.
//
// Low-Mach-number equations (Le Quere et al. 2005, ESAIM: M2AN 39(3) 609, the benchmark's model;
// Paolucci 1982, SAND82-8257, for the split into P and p), here steady in the particle units (k =
// 1), unknowns (u, p, T), p the hydrodynamic pressure; P the thermodynamic pressure, uniform:
//   n = n(P, T)                 (equation of state, low_mach_eos.hpp; ideal gas n = P/(k T))
//   div(n u) = 0                (mass; steady form of div u = -(1/rho) D rho/Dt)
//   m n (u . grad) u + grad p - div(2 eta S(u) - 2/3 eta div u I) = m (n - n_mean) g
//   n c_p u . grad T = div(kappa grad T) + Q      (dP/dt = 0 in a steady state)
//   int n(P, T) dV = N          (closed box: P from its mass; ideal gas P = N k / int dV/T)
// Weak forms: momentum with the symmetric gradient S(u); mass in the conservative form
// -int q div(n u) = 0, so q = 1 (the sum of the Q1 basis) states global mass conservation
// exactly and the pinned pressure DoF drops a redundant equation; energy as in the Boussinesq
// kernel. n_mean = N/|Omega| is the mean density, so the buoyancy has zero mean.
//
// Newton's method: exact Jacobian at fixed P, plus the global coupling through P, a rank-one
// term (dR/dP)(dP/dx)^T, handled by the Sherman-Morrison formula with the same factorisation
// (one extra back-substitution): the full Newton step, no fixed-point lag on P.

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/fe_field_function.h>
#include <deal.II/numerics/solution_transfer.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <set>
#include <stdexcept>

#include "continuum/boussinesq.templates.hpp" // detail::line_maximum
#include "continuum/fields.templates.hpp"
#include "continuum/low_mach.hpp"
#include "continuum/low_mach_eos.hpp"

namespace twinflow::continuum {

namespace detail {

// The cell integrals of the system at the top of this file: cell_rhs = -R, and if
// `with_jacobian`: cell_matrix = dR/dx at fixed P, cell_dR_dP = dR/dP, and cell_dn_dT(j) =
// int dn/dT phi_T_j (for dP/dx = -int dn/dT phi_T / int dn/dP).
template <int dim> class LowMachCellKernel {
public:
  LowMachCellKernel(const dealii::FiniteElement<dim>& fe, const ContinuumParameters& prm)
      : prm_(prm), quadrature_(3), face_quadrature_(3),
        fe_values_(fe, quadrature_,
                   dealii::update_values | dealii::update_gradients |
                       dealii::update_quadrature_points | dealii::update_JxW_values),
        fe_face_values_(fe, face_quadrature_, dealii::update_values | dealii::update_JxW_values),
        n_(fe.n_dofs_per_cell()), u_(quadrature_.size()), grad_T_(quadrature_.size()),
        grad_u_(quadrature_.size()), p_(quadrature_.size()), T_(quadrature_.size()), phi_u_(n_),
        grad_phi_T_(n_), grad_phi_u_(n_), eps_phi_u_(n_), div_phi_u_(n_), phi_p_(n_), phi_T_(n_),
        u_old_(quadrature_.size()), T_old_(quadrature_.size()) {}

  void assemble(const typename dealii::DoFHandler<dim>::active_cell_iterator& cell,
                const dealii::Vector<double>& x, double P, bool with_jacobian,
                double gravity_factor, dealii::FullMatrix<double>& cell_matrix,
                dealii::Vector<double>& cell_rhs, dealii::Vector<double>& cell_dR_dP,
                dealii::Vector<double>& cell_dn_dT, double& dn_dP_integral,
                const LowMachTimeTerms& time) {
    const dealii::FEValuesExtractors::Vector velocities(0);
    const dealii::FEValuesExtractors::Scalar pressure(dim), temperature(dim + 1);
    auto& fv = fe_values_;
    fv.reinit(cell);
    cell_matrix = 0;
    cell_rhs = 0;
    cell_dR_dP = 0;
    cell_dn_dT = 0;
    fv[velocities].get_function_values(x, u_);
    fv[velocities].get_function_gradients(x, grad_u_);
    fv[pressure].get_function_values(x, p_);
    fv[temperature].get_function_values(x, T_);
    fv[temperature].get_function_gradients(x, grad_T_);
    const double inv_dt = time.inverse_time_step;
    if (inv_dt > 0) {
      fv[velocities].get_function_values(*time.old_solution, u_old_);
      fv[temperature].get_function_values(*time.old_solution, T_old_);
    }
    const double m = prm_.particle_mass, cp = prm_.heat_capacity;
    const double n_mean = prm_.number_density, T_ref = prm_.reference_temperature;
    dealii::Tensor<1, dim> g;
    for (int d = 0; d < dim; ++d) g[d] = gravity_factor * prm_.gravity[d];
    for (unsigned q = 0; q < quadrature_.size(); ++q) {
      const DensityState s = number_density(prm_.equation_of_state, P, T_[q]);
      const double eta = prm_.viscosity.at(T_[q], T_ref);
      const double deta = prm_.viscosity.derivative(T_[q], T_ref);
      const double kappa = prm_.conductivity.at(T_[q], T_ref);
      const double dkappa = prm_.conductivity.derivative(T_[q], T_ref);
      std::array<double, 3> x3{{0, 0, 0}};
      for (int d = 0; d < dim; ++d) x3[d] = fv.quadrature_point(q)[d];
      const double source = heat_source_density(prm_, x3);
      const dealii::SymmetricTensor<2, dim> eps_u = dealii::symmetrize(grad_u_[q]);
      const double div_u = dealii::trace(grad_u_[q]);
      const dealii::Tensor<1, dim> advection = grad_u_[q] * u_[q]; // (u . grad) u
      const double u_grad_T = u_[q] * grad_T_[q];
      const double JxW = fv.JxW(q);
      // Transient: (u - u_old)/dt, (n - n_old)/dt, (T - T_old)/dt, (P - P_old)/dt.
      const dealii::Tensor<1, dim> du = inv_dt > 0 ? u_[q] - u_old_[q] : dealii::Tensor<1, dim>();
      const double dT = inv_dt > 0 ? T_[q] - T_old_[q] : 0.0;
      const double n_old =
          inv_dt > 0 ? number_density(prm_.equation_of_state, time.old_pressure, T_old_[q]).n : 0.0;
      const double dP = P - time.old_pressure;
      for (unsigned k = 0; k < n_; ++k) {
        phi_u_[k] = fv[velocities].value(k, q);
        grad_phi_u_[k] = fv[velocities].gradient(k, q);
        eps_phi_u_[k] = fv[velocities].symmetric_gradient(k, q);
        div_phi_u_[k] = fv[velocities].divergence(k, q);
        phi_p_[k] = fv[pressure].value(k, q);
        phi_T_[k] = fv[temperature].value(k, q);
        grad_phi_T_[k] = fv[temperature].gradient(k, q);
      }
      if (with_jacobian) dn_dP_integral += s.n_P * JxW;
      for (unsigned i = 0; i < n_; ++i) {
        // Weak residual (equations at the top of this file); viscous stress
        // 2 eta S(u) - 2/3 eta div u I (Le Quere et al. 2005) against grad v.
        const double viscous_i =
            2 * eta * (eps_u * eps_phi_u_[i]) - 2.0 / 3.0 * eta * div_u * div_phi_u_[i];
        const double residual = m * s.n * (advection * phi_u_[i]) + viscous_i -
                                p_[q] * div_phi_u_[i] - m * (s.n - n_mean) * (g * phi_u_[i]) -
                                phi_p_[i] * (s.n * div_u + s.n_T * u_grad_T) +
                                cp * s.n * u_grad_T * phi_T_[i] +
                                kappa * (grad_T_[q] * grad_phi_T_[i]) - source * phi_T_[i];
        // Implicit Euler: m n du/dt . v - q dn/dt + (n c_p dT/dt - dP/dt) w (Le Quere et al.
        // 2005; the dP/dt of the energy equation vanishes in a steady state).
        const double transient =
            inv_dt > 0 ? inv_dt * (m * s.n * (du * phi_u_[i]) - phi_p_[i] * (s.n - n_old) +
                                   (cp * s.n * dT - dP) * phi_T_[i])
                       : 0.0;
        cell_rhs(i) -= (residual + transient) * JxW;
        if (!with_jacobian) continue;
        // dR/dP: n and n_T depend on P (grad n = n_T grad T at uniform P).
        cell_dR_dP(i) +=
            (m * s.n_P * (advection * phi_u_[i]) - m * s.n_P * (g * phi_u_[i]) -
             phi_p_[i] * (s.n_P * div_u + s.n_TP * u_grad_T) + cp * s.n_P * u_grad_T * phi_T_[i]) *
            JxW;
        if (inv_dt > 0)
          cell_dR_dP(i) += inv_dt *
                           (m * s.n_P * (du * phi_u_[i]) - phi_p_[i] * s.n_P +
                            (cp * s.n_P * dT - 1.0) * phi_T_[i]) *
                           JxW;
        cell_dn_dT(i) += s.n_T * phi_T_[i] * JxW;
        const double stress_u_i =
            2 * (eps_u * eps_phi_u_[i]) - 2.0 / 3.0 * div_u * div_phi_u_[i]; // viscous_i / eta
        for (unsigned j = 0; j < n_; ++j) {
          // Exact derivative of the residual above in direction (phi_u_j, phi_p_j, phi_T_j).
          const double div_j = div_phi_u_[j];
          const double u_grad_T_j = phi_u_[j] * grad_T_[q] + u_[q] * grad_phi_T_[j];
          const double jacobian =
              m * s.n * ((grad_phi_u_[j] * u_[q] + grad_u_[q] * phi_u_[j]) * phi_u_[i]) +
              m * s.n_T * phi_T_[j] * (advection * phi_u_[i]) +
              2 * eta * (eps_phi_u_[j] * eps_phi_u_[i]) - 2.0 / 3.0 * eta * div_j * div_phi_u_[i] +
              deta * phi_T_[j] * stress_u_i - phi_p_[j] * div_phi_u_[i] -
              m * s.n_T * phi_T_[j] * (g * phi_u_[i]) -
              phi_p_[i] * (s.n * div_j + s.n_T * phi_T_[j] * div_u + s.n_T * u_grad_T_j +
                           s.n_TT * phi_T_[j] * u_grad_T) +
              cp * s.n_T * phi_T_[j] * u_grad_T * phi_T_[i] + cp * s.n * u_grad_T_j * phi_T_[i] +
              kappa * (grad_phi_T_[j] * grad_phi_T_[i]) +
              dkappa * phi_T_[j] * (grad_T_[q] * grad_phi_T_[i]);
          const double transient_j =
              inv_dt > 0 ? inv_dt * (m * s.n * (phi_u_[j] * phi_u_[i]) +
                                     m * s.n_T * phi_T_[j] * (du * phi_u_[i]) -
                                     phi_p_[i] * s.n_T * phi_T_[j] +
                                     cp * (s.n + s.n_T * dT) * phi_T_[j] * phi_T_[i])
                         : 0.0;
          cell_matrix(i, j) += (jacobian + transient_j) * JxW;
        }
      }
    }
    // Prescribed heat flux into the domain through flux walls: - int_Gamma h phi_T.
    for (const auto& face : cell->face_iterators()) {
      if (!face->at_boundary()) continue;
      const int d = face->boundary_id() / 2, side = face->boundary_id() % 2;
      const auto& b = prm_.boundary[d];
      if (b.periodic || b.fixed_temperature[side] || b.heat_flux[side] == 0.0) continue;
      fe_face_values_.reinit(cell, face);
      for (unsigned q = 0; q < face_quadrature_.size(); ++q)
        for (unsigned i = 0; i < n_; ++i)
          cell_rhs(i) +=
              b.heat_flux[side] * fe_face_values_[temperature].value(i, q) * fe_face_values_.JxW(q);
    }
  }

private:
  const ContinuumParameters& prm_;
  const dealii::QGauss<dim> quadrature_;
  const dealii::QGauss<dim - 1> face_quadrature_;
  dealii::FEValues<dim> fe_values_;
  dealii::FEFaceValues<dim> fe_face_values_;
  const unsigned n_;
  std::vector<dealii::Tensor<1, dim>> u_, grad_T_;
  std::vector<dealii::Tensor<2, dim>> grad_u_;
  std::vector<double> p_, T_;
  std::vector<dealii::Tensor<1, dim>> phi_u_, grad_phi_T_;
  std::vector<dealii::Tensor<2, dim>> grad_phi_u_;
  std::vector<dealii::SymmetricTensor<2, dim>> eps_phi_u_;
  std::vector<double> div_phi_u_, phi_p_, phi_T_;
  std::vector<dealii::Tensor<1, dim>> u_old_;
  std::vector<double> T_old_;
};

// Number density n(P, T) from the temperature component, for the field output.
template <int dim> class DensityPostprocessor : public dealii::DataPostprocessorScalar<dim> {
public:
  DensityPostprocessor(EquationOfState eos, double P)
      : dealii::DataPostprocessorScalar<dim>("n", dealii::update_values), eos_(eos), P_(P) {}
  void evaluate_vector_field(const dealii::DataPostprocessorInputs::Vector<dim>& input,
                             std::vector<dealii::Vector<double>>& out) const override {
    for (unsigned q = 0; q < input.solution_values.size(); ++q)
      out[q](0) = number_density(eos_, P_, input.solution_values[q](dim + 1)).n;
  }

private:
  EquationOfState eos_;
  double P_;
};

} // namespace detail

template <int dim>
LowMachProblem<dim>::LowMachProblem(const ContinuumParameters& parameters)
    : prm_(parameters), numbers_(dimensionless_numbers(parameters)),
      fe_(dealii::FE_Q<dim>(2), dim, dealii::FE_Q<dim>(1), 1, dealii::FE_Q<dim>(2), 1),
      dof_handler_(triangulation_) {
  check(prm_);
  if (prm_.dim != dim) throw std::invalid_argument("LowMachProblem: dimension mismatch");
  double volume = 1;
  for (int d = 0; d < dim; ++d) volume *= prm_.box[d];
  total_particles_ = prm_.number_density * volume;                        // N = n_mean |Omega|
  reference_pressure_ = prm_.number_density * prm_.reference_temperature; // p0 = n k T_ref, k = 1
  // Le Quere 2005: Nu = (H / (kappa(T0) dT)) int kappa dT/dx over the wall; T0 = T_ref.
  reference_flux_ =
      numbers_.heated_direction < 0
          ? 0.0
          : prm_.conductivity.at(prm_.reference_temperature, prm_.reference_temperature) *
                std::abs(numbers_.temperature_difference) / numbers_.height;
  P_ = reference_pressure_;
}

template <int dim> ContinuumResult LowMachProblem<dim>::run(const std::filesystem::path& out) {
  ContinuumResult result;
  result.model = "low-mach";
  result.dim = dim;
  result.numbers = numbers_;
  {
    detail::ScopedTimer timer(times_.setup);
    detail::make_box_mesh(triangulation_, prm_);
  }
  if (prm_.transient()) {
    run_transient();
    {
      detail::ScopedTimer timer(times_.postprocess);
      normalize_pressure();
      postprocess(result);
    }
    if (!out.empty()) {
      detail::ScopedTimer timer(times_.output);
      output_fields(out, result);
    }
    result.times = times_;
    return result;
  }
  double previous_nusselt = 0;
  for (level_ = 0; level_ <= prm_.refinements; ++level_) {
    const auto start = std::chrono::steady_clock::now();
    const int iterations_before = newton_iterations_;
    if (level_ == 0) {
      setup_dofs();
      initial_guess();
      solve_with_continuation();
    } else {
      refine_mesh_and_transfer();
      int iterations = 0;
      if (!newton(1.0, iterations))
        throw std::runtime_error("low-Mach Newton did not converge after refinement to level " +
                                 std::to_string(level_));
    }
    update_thermodynamic_pressure(solution_);
    MeshLevel m;
    m.level = level_;
    m.cells = detail::current_cells(triangulation_, prm_);
    m.dofs = dof_handler_.n_dofs();
    {
      detail::ScopedTimer timer(times_.postprocess);
      m.nusselt = volume_nusselt();
    }
    m.change_in_nusselt = level_ == 0 ? 0.0 : m.nusselt - previous_nusselt;
    previous_nusselt = m.nusselt;
    m.pressure_ratio = P_ / reference_pressure_;
    m.newton_iterations = newton_iterations_ - iterations_before;
    m.wall_time = detail::seconds_since(start);
    result.mesh_study.push_back(m);
    std::cout << "continuum: level " << level_ << ", " << m.dofs << " DoFs, Nu = " << m.nusselt
              << ", P/p0 = " << m.pressure_ratio << ", " << m.newton_iterations
              << " Newton iterations, " << m.wall_time << " s" << std::endl;
  }
  {
    detail::ScopedTimer timer(times_.postprocess);
    normalize_pressure();
    postprocess(result);
  }
  if (!out.empty()) {
    detail::ScopedTimer timer(times_.output);
    output_fields(out, result);
  }
  result.times = times_;
  return result;
}

template <int dim> void LowMachProblem<dim>::setup_dofs() {
  detail::ScopedTimer timer(times_.setup);
  dof_handler_.distribute_dofs(fe_);
  make_constraints();
  // Couplings of the Jacobian: no pressure-pressure block; the mass equation sees T (through n).
  const unsigned p = dim;
  dealii::Table<2, dealii::DoFTools::Coupling> coupling(dim + 2, dim + 2);
  for (unsigned c = 0; c < dim + 2; ++c)
    for (unsigned d = 0; d < dim + 2; ++d)
      coupling[c][d] = (c == p && d == p) ? dealii::DoFTools::none : dealii::DoFTools::always;
  dealii::DynamicSparsityPattern dsp(dof_handler_.n_dofs());
  dealii::DoFTools::make_sparsity_pattern(dof_handler_, coupling, dsp, zero_constraints_, false);
  sparsity_pattern_.copy_from(dsp);
  jacobian_.reinit(sparsity_pattern_);
  for (auto* v : {&solution_, &evaluation_point_, &newton_update_, &residual_,
                  &residual_P_derivative_, &pressure_gradient_})
    v->reinit(dof_handler_.n_dofs());
}

template <int dim> void LowMachProblem<dim>::make_constraints() {
  // The same walls as BoussinesqProblem::make_constraints.
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar pressure(dim), temperature(dim + 1);
  const unsigned n_components = dim + 2;
  std::set<dealii::types::boundary_id> free_slip_walls;
  for (const bool homogeneous : {false, true}) {
    auto& c = homogeneous ? zero_constraints_ : nonzero_constraints_;
    c.clear();
    dealii::DoFTools::make_hanging_node_constraints(dof_handler_, c);
    detail::add_periodicity(dof_handler_, prm_, c);
    for (int d = 0; d < dim; ++d) {
      const auto& b = prm_.boundary[d];
      if (b.periodic) continue;
      for (int side = 0; side < 2; ++side) {
        const dealii::types::boundary_id id = 2 * d + side;
        if (b.fixed_temperature[side]) {
          const double value = homogeneous ? 0.0 : b.temperature[side];
          dealii::VectorTools::interpolate_boundary_values(
              dof_handler_, id, dealii::Functions::ConstantFunction<dim>(value, n_components), c,
              fe_.component_mask(temperature));
        }
        if (b.no_slip)
          dealii::VectorTools::interpolate_boundary_values(
              dof_handler_, id, dealii::Functions::ZeroFunction<dim>(n_components), c,
              fe_.component_mask(velocities));
        else
          free_slip_walls.insert(id);
      }
    }
    if (!free_slip_walls.empty())
      dealii::VectorTools::compute_no_normal_flux_constraints(dof_handler_, 0, free_slip_walls, c);
    detail::pin_free_translations(dof_handler_, prm_, c);
    // p is fixed only up to a constant; pin one value (its mass equation is the sum of the
    // others: conservative form).
    for (const auto i : dealii::DoFTools::extract_dofs(dof_handler_, fe_.component_mask(pressure)))
      if (!c.is_constrained(i)) {
        c.add_line(i);
        break;
      }
    c.close();
  }
}

template <int dim> void LowMachProblem<dim>::initial_guess() {
  // At rest with the linear conduction profile between the walls of the heated direction.
  const int d = numbers_.heated_direction;
  const auto& b = prm_.boundary[std::max(d, 0)];
  const double T_ref = prm_.reference_temperature, H = numbers_.height;
  const dealii::VectorFunctionFromScalarFunctionObject<dim> initial(
      [&](const dealii::Point<dim>& x) {
        return d < 0 ? T_ref : b.temperature[0] + (b.temperature[1] - b.temperature[0]) * x[d] / H;
      },
      dim + 1, dim + 2);
  dealii::VectorTools::interpolate(dof_handler_, initial, solution_);
  nonzero_constraints_.distribute(solution_);
  update_thermodynamic_pressure(solution_);
}

template <int dim>
void LowMachProblem<dim>::update_thermodynamic_pressure(const dealii::Vector<double>& x) {
  // Closed box: int n(P, T) dV = N (Le Quere et al. 2005: P = M R / int dV/T for the
  // ideal gas).
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(fe_, quadrature,
                                  dealii::update_values | dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  std::vector<double> T(quadrature.size());
  double previous_step = HUGE_VAL;
  for (int it = 0; it < 50; ++it) {
    double mass = 0, dmass = 0;
    for (const auto& cell : dof_handler_.active_cell_iterators()) {
      fe_values.reinit(cell);
      fe_values[temperature].get_function_values(x, T);
      for (unsigned q = 0; q < quadrature.size(); ++q) {
        if (!(T[q] > 0))
          throw std::runtime_error("low-Mach: temperature <= 0 at a quadrature point");
        const DensityState s = number_density(prm_.equation_of_state, P_, T[q]);
        mass += s.n * fe_values.JxW(q);
        dmass += s.n_P * fe_values.JxW(q);
      }
    }
    const double step = (mass - total_particles_) / dmass;
    P_ -= step;
    if (std::abs(step) <= 1e-14 * std::abs(P_)) return;
    // The mass sums ~1e5 quadrature terms in 3D: its round-off can keep the step above 1e-14 P.
    // Stalled steps that small are converged.
    if (std::abs(step) >= 0.5 * previous_step && std::abs(step) <= 1e-10 * std::abs(P_)) return;
    previous_step = std::abs(step);
  }
  throw std::runtime_error("low-Mach: the thermodynamic pressure did not converge");
}

template <int dim> double LowMachProblem<dim>::assemble(bool with_jacobian, double gravity_factor) {
  update_thermodynamic_pressure(evaluation_point_);
  detail::ScopedTimer timer(times_.assembly);
  if (with_jacobian) {
    jacobian_ = 0;
    residual_P_derivative_ = 0;
    pressure_gradient_ = 0;
  }
  residual_ = 0;
  dn_dP_total_ = 0;
  detail::LowMachCellKernel<dim> kernel(fe_, prm_);
  const unsigned n = fe_.n_dofs_per_cell();
  dealii::FullMatrix<double> cell_matrix(n, n);
  dealii::Vector<double> cell_rhs(n), cell_dR_dP(n), cell_dn_dT(n);
  std::vector<dealii::types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    kernel.assemble(cell, evaluation_point_, P_, with_jacobian, gravity_factor, cell_matrix,
                    cell_rhs, cell_dR_dP, cell_dn_dT, dn_dP_total_, time_terms_);
    cell->get_dof_indices(dofs);
    if (with_jacobian) {
      zero_constraints_.distribute_local_to_global(cell_matrix, cell_rhs, dofs, jacobian_,
                                                   residual_);
      zero_constraints_.distribute_local_to_global(cell_dR_dP, dofs, residual_P_derivative_);
      for (unsigned i = 0; i < n; ++i) pressure_gradient_(dofs[i]) += cell_dn_dT(i); // raw
    } else
      zero_constraints_.distribute_local_to_global(cell_rhs, dofs, residual_);
  }
  // dP/dx_j = -int dn/dT phi_T_j dV / int dn/dP dV (implicit function of the mass constraint)
  if (with_jacobian) pressure_gradient_ *= -1.0 / dn_dP_total_;
  return residual_.l2_norm();
}

template <int dim> void LowMachProblem<dim>::solve_linear_system() {
  // (J + b c^T) dx = r with b = dR/dP, c = dP/dx: Sherman-Morrison (Golub & Van Loan, Matrix
  // Computations, 4th ed., sec. 2.1.4): z1 = J^-1 r, z2 = J^-1 b,
  // dx = z1 - z2 (c . z1) / (1 + c . z2); c acts on the distributed (full) vectors.
  detail::ScopedTimer timer(times_.solve);
  direct_solver_.initialize(jacobian_);
  dealii::Vector<double> z2(residual_P_derivative_.size());
  direct_solver_.vmult(newton_update_, residual_);
  direct_solver_.vmult(z2, residual_P_derivative_);
  zero_constraints_.distribute(newton_update_);
  zero_constraints_.distribute(z2);
  const double c_z1 = pressure_gradient_ * newton_update_, c_z2 = pressure_gradient_ * z2;
  newton_update_.add(-c_z1 / (1.0 + c_z2), z2);
}

template <int dim> bool LowMachProblem<dim>::newton(double gravity_factor, int& iterations) {
  // As BoussinesqProblem::newton: relative updates of velocity and temperature, line search.
  std::vector<bool> is_velocity(dof_handler_.n_dofs(), false);
  for (const auto i : dealii::DoFTools::extract_dofs(
           dof_handler_, fe_.component_mask(dealii::FEValuesExtractors::Vector(0))))
    is_velocity[i] = true;
  const dealii::IndexSet temperature_dofs = dealii::DoFTools::extract_dofs(
      dof_handler_, fe_.component_mask(dealii::FEValuesExtractors::Scalar(dim + 1)));
  auto field_norms = [&](const dealii::Vector<double>& v) {
    double nu = 0, nt = 0;
    for (unsigned i = 0; i < v.size(); ++i) {
      if (is_velocity[i]) nu += v[i] * v[i];
      if (temperature_dofs.is_element(i)) nt += v[i] * v[i];
    }
    return std::array<double, 2>{{std::sqrt(nu), std::sqrt(nt)}};
  };
  const double n_dofs_root = std::sqrt(static_cast<double>(dof_handler_.n_dofs()));
  const double velocity_floor = numbers_.velocity_scale * n_dofs_root;
  const double temperature_floor =
      std::max(std::abs(numbers_.temperature_difference), prm_.reference_temperature) * n_dofs_root;

  evaluation_point_ = solution_;
  double residual_norm = assemble(true, gravity_factor);
  for (int it = 0; it < prm_.max_newton_iterations; ++it) {
    solve_linear_system();
    double step = 1.0, new_norm = 0;
    for (;;) {
      evaluation_point_ = solution_;
      evaluation_point_.add(step, newton_update_);
      bool positive = true; // the ideal gas needs T > 0 everywhere
      try {
        new_norm = assemble(false, gravity_factor);
      } catch (const std::runtime_error&) {
        positive = false;
        new_norm = std::numeric_limits<double>::infinity();
      }
      if ((positive && new_norm < residual_norm) || step < 1.0 / 32) break;
      step /= 2;
    }
    if (!std::isfinite(new_norm)) return false;
    solution_ = evaluation_point_;
    ++iterations;
    ++newton_iterations_;
    const auto dx = field_norms(newton_update_), x = field_norms(solution_);
    const double change = std::max(step * dx[0] / (x[0] + 1e-3 * velocity_floor),
                                   step * dx[1] / (x[1] + 1e-3 * temperature_floor));
    if (std::getenv("TWINFLOW_NEWTON_DEBUG"))
      std::cout << "  newton " << it << ": residual " << residual_norm << " -> " << new_norm
                << ", step " << step << ", change " << change << ", P " << P_ << std::endl;
    if (change < prm_.newton_tolerance) return true;
    residual_norm = assemble(true, gravity_factor);
  }
  return false;
}

template <int dim> void LowMachProblem<dim>::solve_with_continuation() {
  // As BoussinesqProblem: Ra in factor-10 steps from the start value, geometric mid-steps on
  // failure.
  const double target = numbers_.rayleigh, start = prm_.continuation_start_rayleigh;
  std::vector<double> factors;
  // (1 - 1e-12): Ra computed from g may exceed a power of 10 by round-off (no repeated step).
  for (double ra = start; ra < target * (1 - 1e-12) && target > 0; ra *= 10)
    factors.push_back(ra / target);
  factors.push_back(1.0);
  double reached = 0.0;
  dealii::Vector<double> last_converged = solution_;
  int failures = 0;
  for (std::size_t k = 0; k < factors.size();) {
    int iterations = 0;
    if (newton(factors[k], iterations)) {
      last_converged = solution_;
      reached = factors[k];
      continuation_rayleigh_.push_back(factors[k] * target);
      std::cout << "continuum: Ra = " << factors[k] * target << " converged in " << iterations
                << " Newton iterations" << std::endl;
      ++k;
    } else {
      if (++failures > 10)
        throw std::runtime_error("low-Mach Newton did not converge on the way to Ra = " +
                                 std::to_string(factors[k] * target));
      solution_ = last_converged;
      const double from = reached > 0 ? reached : factors[k] / 10;
      factors.insert(factors.begin() + k, std::sqrt(from * factors[k]));
    }
  }
}

template <int dim> void LowMachProblem<dim>::run_transient() {
  const auto start = std::chrono::steady_clock::now();
  {
    detail::ScopedTimer timer(times_.setup);
    detail::refine_uniformly(triangulation_, prm_, prm_.refinements);
  }
  setup_dofs();
  // At rest and at T_ref, the walls at their temperatures from t = 0 on (Le Quere 2005's
  // initial state: uniform T0 and p0).
  solution_ = 0;
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  for (const auto i : dealii::DoFTools::extract_dofs(dof_handler_, fe_.component_mask(temperature)))
    solution_[i] = prm_.reference_temperature;
  nonzero_constraints_.distribute(solution_);
  update_thermodynamic_pressure(solution_);
  const double dt_max = prm_.time_step;
  int report = 0;
  while (time_ < prm_.end_time * (1 - 1e-12)) {
    const double dt = std::min(dt_max, prm_.end_time - time_);
    old_solution_ = solution_;
    time_terms_ = {&old_solution_, P_, 1.0 / dt};
    int iterations = 0;
    if (!newton(1.0, iterations))
      throw std::runtime_error("low-Mach Newton did not converge in the time step to t = " +
                               std::to_string(time_ + dt));
    time_ += dt;
    ++time_steps_;
    update_thermodynamic_pressure(solution_);
    if (time_ >= (report + 1) * 0.1 * prm_.end_time * (1 - 1e-12)) {
      report = static_cast<int>(time_ / (0.1 * prm_.end_time) + 1e-9);
      std::cout << "continuum: t = " << time_ << ", Nu (volume) = " << volume_nusselt()
                << ", P/p0 = " << P_ / reference_pressure_ << ", " << iterations
                << " Newton iterations" << std::endl;
    }
  }
  time_terms_ = {}; // postprocessing sees the steady operator
  MeshLevel m;
  m.level = prm_.refinements;
  m.cells = detail::current_cells(triangulation_, prm_);
  m.dofs = dof_handler_.n_dofs();
  m.nusselt = volume_nusselt();
  m.pressure_ratio = P_ / reference_pressure_;
  m.newton_iterations = newton_iterations_;
  m.wall_time = detail::seconds_since(start);
  std::cout << "continuum: " << time_steps_ << " time steps, " << m.dofs << " DoFs, "
            << m.newton_iterations << " Newton iterations, " << m.wall_time << " s" << std::endl;
  mesh_study_transient_ = m;
}

template <int dim> void LowMachProblem<dim>::normalize_pressure() {
  const double mean =
      dealii::VectorTools::compute_mean_value(dof_handler_, dealii::QGauss<dim>(3), solution_, dim);
  for (const auto i : dealii::DoFTools::extract_dofs(
           dof_handler_, fe_.component_mask(dealii::FEValuesExtractors::Scalar(dim))))
    solution_[i] -= mean;
}

template <int dim> void LowMachProblem<dim>::refine_mesh_and_transfer() {
  detail::ScopedTimer timer(times_.setup);
  dealii::SolutionTransfer<dim> transfer(dof_handler_);
  detail::flag_uniform_refinement(triangulation_, prm_);
  triangulation_.prepare_coarsening_and_refinement();
  const dealii::Vector<double> coarse_solution = solution_;
  transfer.prepare_for_coarsening_and_refinement(coarse_solution);
  triangulation_.execute_coarsening_and_refinement();
  setup_dofs();
  dealii::Vector<double> transferred(dof_handler_.n_dofs());
  transfer.interpolate(coarse_solution, transferred);
  solution_ = transferred;
  nonzero_constraints_.distribute(solution_);
}

template <int dim> double LowMachProblem<dim>::volume_nusselt() const {
  // Steady: div(n c_p u (T - T_ref) - kappa grad T) = c_p (T - T_ref) div(n u) = 0, so the mean
  // of its d-component over the box is the wall heat flux; over kappa(T_ref) dT / H
  // (Le Quere 2005 Nu normalisation).
  const int d = numbers_.heated_direction;
  if (d < 0) return 0.0;
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(fe_, quadrature,
                                  dealii::update_values | dealii::update_gradients |
                                      dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  std::vector<dealii::Tensor<1, dim>> u(quadrature.size()), grad_T(quadrature.size());
  std::vector<double> T(quadrature.size());
  const double cp = prm_.heat_capacity, T_ref = prm_.reference_temperature;
  const double sign = numbers_.temperature_difference > 0 ? 1.0 : -1.0;
  double flux = 0, volume = 0;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    fe_values.reinit(cell);
    fe_values[velocities].get_function_values(solution_, u);
    fe_values[temperature].get_function_values(solution_, T);
    fe_values[temperature].get_function_gradients(solution_, grad_T);
    for (unsigned q = 0; q < quadrature.size(); ++q) {
      const double n = number_density(prm_.equation_of_state, P_, T[q]).n;
      flux +=
          (cp * n * u[q][d] * (T[q] - T_ref) - prm_.conductivity.at(T[q], T_ref) * grad_T[q][d]) *
          fe_values.JxW(q);
      volume += fe_values.JxW(q);
    }
  }
  return sign * flux / volume / reference_flux_;
}

template <int dim> void LowMachProblem<dim>::wall_nusselt(ContinuumResult& result) const {
  // Local Nu = +-kappa(T) n.grad T / (kappa(T_ref) dT / H) on the two walls of the heated
  // direction (Le Quere 2005 Nu).
  const int d = numbers_.heated_direction;
  if (d < 0) return;
  const dealii::QGauss<dim - 1> face_quadrature(3);
  dealii::FEFaceValues<dim> fe_face_values(
      fe_, face_quadrature,
      dealii::update_values | dealii::update_gradients | dealii::update_normal_vectors |
          dealii::update_quadrature_points | dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  std::vector<double> T(face_quadrature.size());
  std::vector<dealii::Tensor<1, dim>> grad_T(face_quadrature.size());
  const double sign = numbers_.temperature_difference > 0 ? 1.0 : -1.0;
  for (int side = 0; side < 2; ++side) {
    WallNusselt wall;
    wall.direction = d;
    wall.side = side;
    double area = 0, integral = 0;
    for (const auto& cell : dof_handler_.active_cell_iterators())
      for (const auto& face : cell->face_iterators()) {
        if (!face->at_boundary() || face->boundary_id() != static_cast<unsigned>(2 * d + side))
          continue;
        fe_face_values.reinit(cell, face);
        fe_face_values[temperature].get_function_values(solution_, T);
        fe_face_values[temperature].get_function_gradients(solution_, grad_T);
        for (unsigned q = 0; q < face_quadrature.size(); ++q) {
          const double nu = sign * (side == 0 ? 1.0 : -1.0) *
                            prm_.conductivity.at(T[q], prm_.reference_temperature) *
                            (grad_T[q] * fe_face_values.normal_vector(q)) / reference_flux_;
          std::array<double, 3> x{{0, 0, 0}};
          for (int k = 0; k < dim; ++k) x[k] = fe_face_values.quadrature_point(q)[k];
          wall.points.push_back(x);
          wall.local.push_back(nu);
          integral += nu * fe_face_values.JxW(q);
          area += fe_face_values.JxW(q);
        }
      }
    wall.average = integral / area;
    result.walls.push_back(wall);
  }
}

template <int dim>
void LowMachProblem<dim>::consistent_wall_nusselt(ContinuumResult& result) const {
  // Heat into the fluid through a fixed-temperature wall, int_wall kappa dT/dn (n outward), from
  // the weak energy equation tested with w = 1 on that wall's T nodes, 0 elsewhere:
  // Q = int (n c_p u.grad T w + kappa grad T.grad w - source w) (the consistent flux: Gresho,
  // Lee, Sani et al., Int. J. Numer. Meth. Fluids 7 (1987) 371; converges faster than the wall
  // gradient).
  const int d = numbers_.heated_direction;
  if (d < 0) return;
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(fe_, quadrature,
                                  dealii::update_values | dealii::update_gradients |
                                      dealii::update_quadrature_points | dealii::update_JxW_values);
  std::vector<dealii::Tensor<1, dim>> u(quadrature.size()), grad_T(quadrature.size()),
      grad_w(quadrature.size());
  std::vector<double> T(quadrature.size()), w(quadrature.size());
  const double sign = numbers_.temperature_difference > 0 ? 1.0 : -1.0;
  double area = 1;
  for (int k = 0; k < dim; ++k)
    if (k != d) area *= prm_.box[k];
  for (int side = 0; side < 2; ++side) {
    dealii::Vector<double> indicator(dof_handler_.n_dofs());
    for (const auto i :
         dealii::DoFTools::extract_boundary_dofs(dof_handler_, fe_.component_mask(temperature),
                                                 {dealii::types::boundary_id(2 * d + side)}))
      indicator[i] = 1.0;
    double Q = 0;
    for (const auto& cell : dof_handler_.active_cell_iterators()) {
      fe_values.reinit(cell);
      fe_values[temperature].get_function_values(indicator, w);
      bool touches = false;
      for (const double v : w) touches = touches || v != 0.0;
      if (!touches) continue;
      fe_values[temperature].get_function_gradients(indicator, grad_w);
      fe_values[velocities].get_function_values(solution_, u);
      fe_values[temperature].get_function_values(solution_, T);
      fe_values[temperature].get_function_gradients(solution_, grad_T);
      for (unsigned q = 0; q < quadrature.size(); ++q) {
        std::array<double, 3> x3{{0, 0, 0}};
        for (int k = 0; k < dim; ++k) x3[k] = fe_values.quadrature_point(q)[k];
        const double n = number_density(prm_.equation_of_state, P_, T[q]).n;
        Q += (prm_.heat_capacity * n * (u[q] * grad_T[q]) * w[q] +
              prm_.conductivity.at(T[q], prm_.reference_temperature) * (grad_T[q] * grad_w[q]) -
              heat_source_density(prm_, x3) * w[q]) *
             fe_values.JxW(q);
      }
    }
    result.consistent_wall_nusselt.push_back((side == 0 ? 1.0 : -1.0) * sign * Q /
                                             (area * reference_flux_));
  }
}

template <int dim> void LowMachProblem<dim>::midline_maxima(ContinuumResult& result) const {
  // As the Boussinesq cavity: max u on x = Lx/2, max v on y = Ly/2 in chi(T_ref)/H.
  dealii::Functions::FEFieldFunction<dim> field(dof_handler_, solution_);
  const double scale = numbers_.velocity_scale;
  auto velocity = [&](double x, double y, int component) {
    dealii::Point<dim> point;
    point[0] = x, point[1] = y;
    if (dim == 3) point[dim - 1] = 0.5 * prm_.box[2];
    return field.value(point, component) / scale;
  };
  const double Lx = prm_.box[0], Ly = prm_.box[1];
  // line_maximum evaluates a list of positions per call.
  auto on_line = [&](auto&& f) {
    return [f](const std::vector<double>& positions) {
      std::vector<double> values(positions.size());
      for (std::size_t i = 0; i < positions.size(); ++i) values[i] = f(positions[i]);
      return values;
    };
  };
  result.has_midline_maxima = true;
  result.u_max_vertical_midline = detail::line_maximum(
      on_line([&](double y) { return velocity(0.5 * Lx, y, 0); }), 0.0, Ly, prm_.profile_samples);
  result.u_max_vertical_midline.position /= Ly;
  result.v_max_horizontal_midline = detail::line_maximum(
      on_line([&](double x) { return velocity(x, 0.5 * Ly, 1); }), 0.0, Lx, prm_.profile_samples);
  result.v_max_horizontal_midline.position /= Lx;
}

template <int dim> void LowMachProblem<dim>::postprocess(ContinuumResult& result) {
  update_thermodynamic_pressure(solution_);
  result.dofs = dof_handler_.n_dofs();
  result.cells = detail::current_cells(triangulation_, prm_);
  result.newton_iterations = newton_iterations_;
  result.continuation_rayleigh = continuation_rayleigh_;
  if (prm_.transient()) result.mesh_study = {mesh_study_transient_};
  result.nusselt = result.mesh_study.back().nusselt;
  result.time = time_;
  result.time_steps = time_steps_;
  result.thermodynamic_pressure = P_;
  result.pressure_ratio = P_ / reference_pressure_;
  wall_nusselt(result);
  consistent_wall_nusselt(result);
  midline_maxima(result);
  std::vector<std::string> names;
  for (int d = 0; d < dim; ++d) names.push_back(std::string("u_") + "xyz"[d]);
  names.push_back("p");
  names.push_back("T");
  names.push_back("n"); // the number density n(P, T), compared with the particles'
  const auto density = [&](const dealii::Vector<double>& v) {
    return number_density(prm_.equation_of_state, P_, v(dim + 1)).n;
  };
  result.bins =
      detail::bin_averages(dof_handler_, solution_, names, prm_, MPI_COMM_SELF, {density});
  detail::probe(dof_handler_, solution_, prm_, result);
  result.temperature_min = 1e300, result.temperature_max = -1e300;
  for (const auto i : dealii::DoFTools::extract_dofs(
           dof_handler_, fe_.component_mask(dealii::FEValuesExtractors::Scalar(dim + 1)))) {
    result.temperature_min = std::min(result.temperature_min, solution_[i]);
    result.temperature_max = std::max(result.temperature_max, solution_[i]);
  }
  // n is monotonic in T for the ideal gas; the extremes are at the temperature extremes.
  const double n1 = number_density(prm_.equation_of_state, P_, result.temperature_min).n;
  const double n2 = number_density(prm_.equation_of_state, P_, result.temperature_max).n;
  result.density_min = std::min(n1, n2), result.density_max = std::max(n1, n2);
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(fe_, quadrature,
                                  dealii::update_values | dealii::update_JxW_values);
  std::vector<dealii::Tensor<1, dim>> u(quadrature.size());
  std::vector<double> T(quadrature.size());
  double volume = 0, integral = 0, mass = 0;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    fe_values.reinit(cell);
    fe_values[dealii::FEValuesExtractors::Vector(0)].get_function_values(solution_, u);
    fe_values[dealii::FEValuesExtractors::Scalar(dim + 1)].get_function_values(solution_, T);
    for (unsigned q = 0; q < quadrature.size(); ++q) {
      result.max_speed = std::max(result.max_speed, u[q].norm() / numbers_.velocity_scale);
      integral += T[q] * fe_values.JxW(q);
      mass += number_density(prm_.equation_of_state, P_, T[q]).n * fe_values.JxW(q);
      volume += fe_values.JxW(q);
    }
  }
  result.temperature_mean = integral / volume;
  result.mass_error = mass / total_particles_ - 1.0;
}

template <int dim>
void LowMachProblem<dim>::output_fields(const std::filesystem::path& dir,
                                        ContinuumResult& result) const {
  if (!prm_.write_fields) return;
  std::vector<std::string> names(dim, "velocity");
  names.push_back("p");
  names.push_back("T");
  std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation> kinds(
      dim, dealii::DataComponentInterpretation::component_is_part_of_vector);
  kinds.push_back(dealii::DataComponentInterpretation::component_is_scalar);
  kinds.push_back(dealii::DataComponentInterpretation::component_is_scalar);
  const detail::DensityPostprocessor<dim> density(prm_.equation_of_state, P_);
  dealii::DataOut<dim> data_out;
  data_out.attach_dof_handler(dof_handler_);
  data_out.add_data_vector(solution_, names, dealii::DataOut<dim>::type_dof_data, kinds);
  data_out.add_data_vector(solution_, density);
  data_out.build_patches(2);
  detail::write_hdf5_xdmf(data_out, dir, 0.0, result.files);
}

template <int dim>
dealii::Vector<double> LowMachProblem<dim>::value_at(const dealii::Point<dim>& point) const {
  dealii::Vector<double> value(dim + 2);
  dealii::VectorTools::point_value(dof_handler_, solution_, point, value);
  return value;
}

} // namespace twinflow::continuum
