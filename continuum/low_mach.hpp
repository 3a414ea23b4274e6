#pragma once
// Low-Mach-number natural convection of a variable-density fluid in a closed box (large
// temperature differences, beside the Boussinesq model), a model of FlowProblem
// (flow_problem.hpp). Equations (Le Quere et al. 2005, ESAIM: M2AN 39(3) 609, the benchmark's
// model; Paolucci 1982, SAND82-8257, for the split into P and p), in the particle units (k = 1),
// unknowns (u, p, T), p the hydrodynamic pressure; P the thermodynamic pressure, uniform:
//   n = n(P, T)                 (equation of state, low_mach_eos.hpp; ideal gas n = P/(k T))
//   dn/dt + div(n u) = 0        (mass)
//   m n (du/dt + (u . grad) u) + grad p - div(2 eta S(u) - 2/3 eta div u I) = m (n - n_mean) g
//   n c_p (dT/dt + u . grad T) - dP/dt = div(kappa grad T) + Q
//   int n(P, T) dV = N          (closed box: P from its mass; ideal gas P = N k / int dV/T)
// Weak forms: momentum with the symmetric gradient S(u); mass in the conservative form
// -int q div(n u) = 0, so q = 1 (the sum of the Q1 basis) states global mass conservation
// exactly and the pinned pressure DoF drops a redundant equation; energy as in the Boussinesq
// model. n_mean = N/|Omega| is the mean density, so the buoyancy has zero mean. Steady, or in
// time by implicit Euler steps (Le Quere et al. 2005 with d/dt).
//
// Newton's method: exact Jacobian at fixed P, plus the global coupling through P, a rank-one
// term (dR/dP)(dP/dx)^T (CellSystem), which the serial backend handles by the Sherman-Morrison
// formula with the same factorisation: the full Newton step, no fixed-point lag on P.
// LowMachProblem<dim>: serial and direct, dim = 2 (flow_2d.cpp) and 3 (flow_3d.cpp, thin boxes
// only).

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "continuum/backend_serial.hpp"
#include "continuum/flow_model.hpp"
#include "continuum/flow_problem.hpp"
#include "continuum/low_mach_eos.hpp"

namespace twinflow::continuum {

template <int dim> class LowMachModel : public FlowModel<dim> {
public:
  static constexpr const char* name = "low-mach";
  static constexpr int time_order = 1; // implicit Euler
  static constexpr bool global_scalar = true;

  LowMachModel(const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
               const dealii::FiniteElement<dim>& fe);

  // No pressure-pressure block; the mass equation sees T (through n).
  dealii::Table<2, dealii::DoFTools::Coupling> coupling() const {
    dealii::Table<2, dealii::DoFTools::Coupling> coupling(dim + 2, dim + 2);
    for (unsigned c = 0; c < dim + 2; ++c)
      for (unsigned d = 0; d < dim + 2; ++d)
        coupling[c][d] = (c == dim && d == dim) ? dealii::DoFTools::none : dealii::DoFTools::always;
    return coupling;
  }
  // Steady: as FlowModel; in time, at rest and at T_ref, the walls at their temperatures from
  // t = 0 on (Le Quere 2005's initial state: uniform T0 and p0).
  std::unique_ptr<dealii::Function<dim>> initial_state() const {
    if (!this->prm_.transient() || !this->prm_.initial_temperature.empty())
      return FlowModel<dim>::initial_state();
    const double T_ref = this->prm_.reference_temperature;
    return this->at_rest([T_ref](const dealii::Point<dim>&) { return T_ref; });
  }
  // The number density n(P, T), compared with the particles'.
  std::vector<NamedField> derived_fields() const {
    return {{"n", [this](const dealii::Vector<double>& v) { return density(0.0, v(dim + 1)); }}};
  }
  double density(double /*p*/, double T) const { return number_density(P_, T).n; }
  // Le Quere 2005: Nu = (H / (kappa(T0) dT)) int kappa dT/dx over the wall; T0 = T_ref.
  double nusselt_flux_scale() const {
    return (this->numbers_.temperature_difference > 0 ? 1.0 : -1.0) * reference_flux_;
  }
  double pressure_ratio() const { return P_ / reference_pressure_; }
  std::string state_note() const {
    std::ostringstream note;
    note << ", P/p0 = " << pressure_ratio();
    return note.str();
  }
  double thermodynamic_pressure() const { return P_; }

  // P of the state x from the mass of the box: int n(P, T) dV = N (scalar Newton; one step for
  // the ideal gas). Throws std::runtime_error where T <= 0.
  template <class VectorType>
  void update_derived_state(const dealii::DoFHandler<dim>& dofs, const VectorType& x);
  template <class VectorType>
  void begin_assembly(const dealii::DoFHandler<dim>& dofs, const VectorType& x, bool) {
    update_derived_state(dofs, x);
    dn_dP_total_ = 0;
  }
  // dP/dx_j = -int dn/dT phi_T_j dV / int dn/dP dV (implicit function of the mass constraint)
  template <class VectorType> void end_assembly(VectorType& row) const {
    row *= -1.0 / dn_dP_total_;
  }
  void begin_time_step(double /*time*/) { old_pressure_ = P_; }

  // The cell integrals of the system at the top of this file: cell.rhs = -R, and if
  // `with_jacobian`: cell.matrix = dR/dx at fixed P, cell.column = dR/dP, and cell.row(j) =
  // int dn/dT phi_T_j (for dP/dx = -int dn/dT phi_T / int dn/dP).
  template <class VectorType>
  void assemble_cell(const CellIterator<dim>& cell, const VectorType& x,
                     const AssemblyContext<dim, VectorType>& context, CellSystem& out);

  template <class VectorType>
  void finish_result(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                     const FlowIntegrals& flow, ContinuumResult& result) const;

private:
  double total_particles_ = 0;    // N = n_mean |Omega|
  double reference_pressure_ = 0; // p0 = n_mean k T_ref
  double reference_flux_ = 0;     // kappa(T_ref) |dT| / H (Le Quere 2005 Nu normalisation)
  double P_ = 0;                  // thermodynamic pressure
  double old_pressure_ = 0;       // P at the previous time
  double dn_dP_total_ = 0;        // int dn/dP dV at the last assembly
  CellValues<dim> values_;
  WallTerms<dim> walls_;
  std::vector<dealii::Tensor<1, dim>> u_old_;
  std::vector<double> T_old_;

  // One quadrature point's coefficients and the parts of the residual that no test function
  // changes (assemble_cell's q loop); inv_dt = 0 when steady.
  struct PointTerms {
    DensityState s;
    double eta = 0, deta = 0, kappa = 0, dkappa = 0, source = 0, div_u = 0, u_grad_T = 0;
    double inv_dt = 0, dT = 0, n_old = 0, dP = 0; // transient: (T - T_old), n_old, P - P_old
    dealii::SymmetricTensor<2, dim> eps_u;
    dealii::Tensor<1, dim> advection, du; // (u . grad) u, u - u_old
  };
  PointTerms point_terms(unsigned q, double inv_dt) const;
  double residual(const PointTerms& t, unsigned q, unsigned i,
                  const dealii::Tensor<1, dim>& g) const;
  double pressure_derivative(const PointTerms& t, unsigned i,
                             const dealii::Tensor<1, dim>& g) const;
  double jacobian(const PointTerms& t, unsigned q, unsigned i, unsigned j,
                  const dealii::Tensor<1, dim>& g) const;
};

template <int dim>
LowMachModel<dim>::LowMachModel(const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
                                const dealii::FiniteElement<dim>& fe)
    : FlowModel<dim>(prm, numbers), values_(fe, dealii::QGauss<dim>(3)), walls_(fe, prm),
      u_old_(values_.n_q), T_old_(values_.n_q) {
  double volume = 1;
  for (int d = 0; d < dim; ++d) volume *= prm.box[d];
  total_particles_ = prm.particle_count > 0 ? prm.particle_count
                                            : prm.number_density * volume; // N = n_mean |Omega|
  reference_pressure_ = prm.number_density * prm.reference_temperature;    // p0 = n k T_ref, k = 1
  reference_flux_ =
      numbers.heated_direction < 0
          ? 0.0
          : prm.conductivity.at(prm.reference_temperature, prm.reference_temperature) *
                std::abs(numbers.temperature_difference) / numbers.height;
  P_ = reference_pressure_;
}

template <int dim>
template <class VectorType>
void LowMachModel<dim>::update_derived_state(const dealii::DoFHandler<dim>& dofs,
                                             const VectorType& x) {
  // Closed box: int n(P, T) dV = N (Le Quere et al. 2005: P = M R / int dV/T for the
  // ideal gas).
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(dofs.get_fe(), quadrature,
                                  dealii::update_values | dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  std::vector<double> T(quadrature.size());
  double previous_step = HUGE_VAL;
  for (int it = 0; it < 50; ++it) {
    double mass = 0, dmass = 0;
    for (const auto& cell : dofs.active_cell_iterators()) {
      fe_values.reinit(cell);
      fe_values[temperature].get_function_values(x, T);
      for (unsigned q = 0; q < quadrature.size(); ++q) {
        if (!(T[q] > 0))
          throw std::runtime_error("low-Mach: temperature <= 0 at a quadrature point");
        const DensityState s = number_density(P_, T[q]);
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

template <int dim>
typename LowMachModel<dim>::PointTerms LowMachModel<dim>::point_terms(unsigned q,
                                                                      double inv_dt) const {
  const auto& prm = this->prm_;
  const double T_ref = prm.reference_temperature;
  const auto& [u, grad_u, p, T, grad_T] = values_.state;
  PointTerms t;
  t.s = number_density(P_, T[q]);
  t.eta = prm.viscosity.at(T[q], T_ref);
  t.deta = prm.viscosity.derivative(T[q], T_ref);
  t.kappa = prm.conductivity.at(T[q], T_ref);
  t.dkappa = prm.conductivity.derivative(T[q], T_ref);
  t.source = heat_source_density(prm, values_.point(q));
  t.eps_u = dealii::symmetrize(grad_u[q]);
  t.div_u = dealii::trace(grad_u[q]);
  t.advection = grad_u[q] * u[q]; // (u . grad) u
  t.u_grad_T = u[q] * grad_T[q];
  // Transient: (u - u_old)/dt, (n - n_old)/dt, (T - T_old)/dt, (P - P_old)/dt.
  t.inv_dt = inv_dt;
  t.du = inv_dt > 0 ? u[q] - u_old_[q] : dealii::Tensor<1, dim>();
  t.dT = inv_dt > 0 ? T[q] - T_old_[q] : 0.0;
  t.n_old = inv_dt > 0 ? number_density(old_pressure_, T_old_[q]).n : 0.0;
  t.dP = P_ - old_pressure_;
  return t;
}

// The weak residual (equations at the top of this file) at q against test function i, with
// implicit Euler's time derivatives when transient.
template <int dim>
double LowMachModel<dim>::residual(const PointTerms& t, unsigned q, unsigned i,
                                   const dealii::Tensor<1, dim>& g) const {
  const auto& prm = this->prm_;
  const double m = prm.particle_mass, cp = prm.heat_capacity, n_mean = prm.number_density;
  const auto& [u, grad_u, p, T, grad_T] = values_.state;
  const auto& [phi_u, grad_phi_u, eps_phi_u, div_phi_u, phi_p, phi_T, grad_phi_T] = values_.shape;
  const auto& s = t.s;
  // Viscous stress 2 eta S(u) - 2/3 eta div u I (Le Quere et al. 2005) against grad v.
  const double viscous_i =
      2 * t.eta * (t.eps_u * eps_phi_u[i]) - 2.0 / 3.0 * t.eta * t.div_u * div_phi_u[i];
  const double steady = m * s.n * (t.advection * phi_u[i]) + viscous_i - p[q] * div_phi_u[i] -
                        m * (s.n - n_mean) * (g * phi_u[i]) -
                        phi_p[i] * (s.n * t.div_u + s.n_T * t.u_grad_T) +
                        cp * s.n * t.u_grad_T * phi_T[i] + t.kappa * (grad_T[q] * grad_phi_T[i]) -
                        t.source * phi_T[i];
  // Implicit Euler: m n du/dt . v - q dn/dt + (n c_p dT/dt - dP/dt) w (Le Quere et al.
  // 2005; the dP/dt of the energy equation vanishes in a steady state).
  const double transient =
      t.inv_dt > 0 ? t.inv_dt * (m * s.n * (t.du * phi_u[i]) - phi_p[i] * (s.n - t.n_old) +
                                 (cp * s.n * t.dT - t.dP) * phi_T[i])
                   : 0.0;
  return steady + transient;
}

// dR_i/dP: n and n_T depend on P (grad n = n_T grad T at uniform P).
template <int dim>
double LowMachModel<dim>::pressure_derivative(const PointTerms& t, unsigned i,
                                              const dealii::Tensor<1, dim>& g) const {
  const double m = this->prm_.particle_mass, cp = this->prm_.heat_capacity;
  const auto& [phi_u, grad_phi_u, eps_phi_u, div_phi_u, phi_p, phi_T, grad_phi_T] = values_.shape;
  const auto& s = t.s;
  return m * s.n_P * (t.advection * phi_u[i]) - m * s.n_P * (g * phi_u[i]) -
         phi_p[i] * (s.n_P * t.div_u + s.n_TP * t.u_grad_T) + cp * s.n_P * t.u_grad_T * phi_T[i];
}

// The exact derivative of residual(i) in direction (phi_u_j, phi_p_j, phi_T_j).
template <int dim>
double LowMachModel<dim>::jacobian(const PointTerms& t, unsigned q, unsigned i, unsigned j,
                                   const dealii::Tensor<1, dim>& g) const {
  const double m = this->prm_.particle_mass, cp = this->prm_.heat_capacity;
  const auto& [u, grad_u, p, T, grad_T] = values_.state;
  const auto& [phi_u, grad_phi_u, eps_phi_u, div_phi_u, phi_p, phi_T, grad_phi_T] = values_.shape;
  const auto& s = t.s;
  const double stress_u_i =
      2 * (t.eps_u * eps_phi_u[i]) - 2.0 / 3.0 * t.div_u * div_phi_u[i]; // viscous_i / eta
  const double div_j = div_phi_u[j];
  const double u_grad_T_j = phi_u[j] * grad_T[q] + u[q] * grad_phi_T[j];
  const double steady =
      m * s.n * ((grad_phi_u[j] * u[q] + grad_u[q] * phi_u[j]) * phi_u[i]) +
      m * s.n_T * phi_T[j] * (t.advection * phi_u[i]) + 2 * t.eta * (eps_phi_u[j] * eps_phi_u[i]) -
      2.0 / 3.0 * t.eta * div_j * div_phi_u[i] + t.deta * phi_T[j] * stress_u_i -
      phi_p[j] * div_phi_u[i] - m * s.n_T * phi_T[j] * (g * phi_u[i]) -
      phi_p[i] * (s.n * div_j + s.n_T * phi_T[j] * t.div_u + s.n_T * u_grad_T_j +
                  s.n_TT * phi_T[j] * t.u_grad_T) +
      cp * s.n_T * phi_T[j] * t.u_grad_T * phi_T[i] + cp * s.n * u_grad_T_j * phi_T[i] +
      t.kappa * (grad_phi_T[j] * grad_phi_T[i]) + t.dkappa * phi_T[j] * (grad_T[q] * grad_phi_T[i]);
  const double transient =
      t.inv_dt > 0
          ? t.inv_dt *
                (m * s.n * (phi_u[j] * phi_u[i]) + m * s.n_T * phi_T[j] * (t.du * phi_u[i]) -
                 phi_p[i] * s.n_T * phi_T[j] + cp * (s.n + s.n_T * t.dT) * phi_T[j] * phi_T[i])
          : 0.0;
  return steady + transient;
}

template <int dim>
template <class VectorType>
void LowMachModel<dim>::assemble_cell(const CellIterator<dim>& cell, const VectorType& x,
                                      const AssemblyContext<dim, VectorType>& context,
                                      CellSystem& out) {
  auto& v = values_;
  v.reinit(cell, x);
  const double inv_dt = context.a0; // implicit Euler: 1/dt
  if (inv_dt > 0) v.values_of(*context.previous, u_old_, T_old_);
  const double m = this->prm_.particle_mass, cp = this->prm_.heat_capacity;
  const bool with_jacobian = context.with_jacobian;
  const dealii::Tensor<1, dim>& g = context.gravity;
  const auto& [phi_u, grad_phi_u, eps_phi_u, div_phi_u, phi_p, phi_T, grad_phi_T] = v.shape;
  for (unsigned q = 0; q < v.n_q; ++q) {
    const PointTerms t = point_terms(q, inv_dt);
    const auto& s = t.s;
    const double JxW = v.fe_values.JxW(q);
    v.shape_functions(q);
    if (with_jacobian) dn_dP_total_ += s.n_P * JxW;
    for (unsigned i = 0; i < v.n; ++i) {
      out.rhs(i) -= residual(t, q, i, g) * JxW;
      if (!with_jacobian) continue;
      out.column(i) += pressure_derivative(t, i, g) * JxW;
      if (inv_dt > 0)
        out.column(i) += inv_dt *
                         (m * s.n_P * (t.du * phi_u[i]) - phi_p[i] * s.n_P +
                          (cp * s.n_P * t.dT - 1.0) * phi_T[i]) *
                         JxW;
      out.row(i) += s.n_T * phi_T[i] * JxW;
      for (unsigned j = 0; j < v.n; ++j) out.matrix(i, j) += jacobian(t, q, i, j, g) * JxW;
    }
  }
  walls_.add(cell, x, with_jacobian, out);
}

template <int dim>
template <class VectorType>
void LowMachModel<dim>::finish_result(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                                      const FlowIntegrals& flow, ContinuumResult& result) const {
  result.thermodynamic_pressure = P_;
  result.pressure_ratio = P_ / reference_pressure_;
  result.consistent_wall_nusselt =
      detail::consistent_wall_nusselt(dofs, x, this->prm_, this->numbers_, *this);
  // n is monotonic in T for the ideal gas; the extremes are at the temperature extremes.
  const double n1 = density(0.0, result.temperature_min);
  const double n2 = density(0.0, result.temperature_max);
  result.density_min = std::min(n1, n2), result.density_max = std::max(n1, n2);
  result.mass_error = flow.particles / total_particles_ - 1.0;
  // Not reported by the low-Mach solver before the shared post-processing (issue 26: its
  // summary.json unchanged); flow.kinetic_energy = int (1/2) m n(P, T) |u|^2 is ready.
  result.kinetic_energy = 0;
}

template <int dim> using LowMachProblem = FlowProblem<dim, LowMachModel<dim>, SerialBackend<dim>>;
extern template class FlowProblem<2, LowMachModel<2>, SerialBackend<2>>;
extern template class FlowProblem<3, LowMachModel<3>, SerialBackend<3>>;

} // namespace twinflow::continuum
