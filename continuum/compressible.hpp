#pragma once
// Compressible Navier-Stokes of the DPDE fluid itself in a closed box, a model of FlowProblem
// (flow_problem.hpp) beside Boussinesq and low-Mach: no Boussinesq or low-Mach approximation,
// so the box is stratified by gravity (g H / c^2) and carries sound. Unknowns (u, n, T), number
// density n, particle units (k = 1):
//   dn/dt + div(n u) = 0                                         (mass)
//   m n (du/dt + (u . grad) u) = -grad p + div tau + m n g        (momentum)
//   n c_V (dT/dt + u . grad T) = -T (dp/dT)_n div u + tau : grad u + div(kappa grad T) + Q
//   tau = 2 eta S(u) + (zeta - (2/d) eta) div u I
//   int n dV = N                                                  (closed box: particles fixed)
// (Landau & Lifshitz, Fluid Mechanics, secs. 15 and 49: the internal-energy equation with the
// pressure work T (dp/dT)_n div u and the viscous heating tau : grad u; d the dimension of the
// twin, the particle fluid's own; zeta the bulk viscosity, a parameter.) p(n, T) and c_V from
// compressible_eos.hpp (ideal DPDE: p = n k T, c_V = c_p - k, 000:(3.20), (3.21)); eta(n, T),
// kappa(n, T) the power laws of the other models with their pair parts (parameters.hpp,
// PowerLaw; zeta stays constant); the full gravity m n g (no mean subtracted: the
// hydrostatic pressure gradient is part of the solution).
//
// Elements: Q2 velocity, Q1 density, Q2 temperature (Taylor-Hood in (u, n)). At the Mach numbers
// of the particle scenes (< 0.1) the mass equation is the constraint of a nearly incompressible
// flow and n plays the pressure's part (grad p = p_n grad n + p_T grad T): the (u, n) block is
// a Stokes saddle point, for which Q2/Q1 is inf-sup stable (Brezzi & Fortin 1991) and equal
// order is not. The transport term u . grad n is taken by plain Galerkin (no upwinding): fine
// for smooth subsonic flow, not for shocks (not this twin's business).
// Weak forms: momentum as low-Mach's, with -int p div v; mass integrated by parts,
// int q dn/dt - int grad q . (n u) (walls: u . normal = 0), so the sum of the Q1 basis (q = 1)
// states d/dt int n dV = 0 exactly. Steady, that sum is the zero equation: one mass equation is
// redundant and int n dV = N takes its place. The model adds (int n dV - N) to the mass equation
// of one free density DoF k (the anchor): summing the mass equations then gives int n = N (in
// time: (a0 + 1)(int n - N) = 0), after which every mass equation holds. Its Jacobian row
// int phi_n_j dV is a rank-one term e_k r^T (CellSystem) that the serial backend takes by
// Sherman-Morrison; the assembled matrix carries beta e_k e_k^T (subtracted again in the
// rank-one row) so that it is invertible on its own.
// In time: BDF2 (first step BDF1), one Newton solve per step. CompressibleProblem<dim>: serial
// and direct, dim = 2 (compressible_2d.cpp) and 3 (compressible_3d.cpp, thin boxes only).

#include <deal.II/base/function.h>
#include <deal.II/lac/affine_constraints.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "continuum/backend_serial.hpp"
#include "continuum/compressible_eos.hpp"
#include "continuum/flow_model.hpp"
#include "continuum/flow_problem.hpp"

namespace twinflow::continuum {

// The isothermal hydrostatic density n(x) = N exp(m g . x / (k T)) / int exp(m g . x / (k T)) dV
// of an ideal gas in the box (barometric law, 000 section 3.1's gravity).
inline double isothermal_column_density(const ContinuumParameters& prm, double T,
                                        const std::array<double, 3>& x) {
  double value = prm.number_density;
  for (int d = 0; d < prm.dim; ++d) {
    const double a = prm.particle_mass * prm.gravity[d] / T; // m g_d / (k T), k = 1
    const double aL = a * prm.box[d];
    // exp(a x) / ((1/L) int_0^L exp(a x) dx) = aL exp(a x) / (exp(aL) - 1)
    value *= std::abs(aL) < 1e-12 ? 1.0 : aL * std::exp(a * x[d]) / std::expm1(aL);
  }
  return value;
}

template <int dim> class CompressibleModel : public FlowModel<dim> {
public:
  static constexpr const char* name = "compressible";
  static constexpr bool gauge_pressure = false; // s = n, not a gauge
  static constexpr bool global_scalar = true;   // the particle count (anchor row)
  static constexpr const char* scalar_name = "n";

  CompressibleModel(const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
                    const dealii::FiniteElement<dim>& fe)
      : FlowModel<dim>(prm, numbers), values_(fe, dealii::QGauss<dim>(3)),
        walls_(fe, prm, /*density_field=*/true), c_v_(heat_capacity_v(prm.heat_capacity)),
        grad_n_(values_.n_q), history_u_(values_.n_q), history_n_(values_.n_q),
        history_T_(values_.n_q), dofs_(fe.n_dofs_per_cell()) {
    volume_ = 1;
    for (int d = 0; d < dim; ++d) volume_ *= prm.box[d];
    total_particles_ = prm.particle_count > 0 ? prm.particle_count
                                              : prm.number_density * volume_; // N = n_mean |Omega|
    reference_flux_ =
        numbers.heated_direction < 0
            ? 0.0
            : prm.conductivity.at(prm.reference_temperature, prm.reference_temperature) *
                  std::abs(numbers.temperature_difference) / numbers.height;
  }

  // At rest: T as FlowModel's (the case's expression, else the conduction profile), n the
  // isothermal column at T_ref (a start Newton corrects to the temperature field). Newton likes
  // it better than n at the column's pressure (n ~ 1/T across the box), which took 133
  // iterations and continuation at Ra = 1e4 where this takes 14, and failed a step of 0.05 in
  // time where this takes 0.1.
  std::unique_ptr<dealii::Function<dim>> initial_state() const {
    std::shared_ptr<dealii::Function<dim>> temperature = FlowModel<dim>::initial_state();
    return std::make_unique<InitialState>(this->prm_, std::move(temperature), start_);
  }
  // The pressure p(n, T), for output and bins.
  std::vector<NamedField> derived_fields() const {
    return {{"p", [this](const dealii::Vector<double>& v) {
               return pressure(this->prm_.equation_of_state, v(dim), v(dim + 1)).p;
             }}};
  }
  double density(double n, double /*T*/) const { return n; }
  double conductivity(double n, double T) const {
    return this->prm_.conductivity
        .at(n, T, this->prm_.number_density, this->prm_.reference_temperature)
        .value;
  }
  // Le Quere 2005's Nu normalisation, as low-Mach's: kappa(T_ref) dT / H.
  double nusselt_flux_scale() const {
    return (this->numbers_.temperature_difference > 0 ? 1.0 : -1.0) * reference_flux_;
  }
  // The mean pressure over p0 = n0 k T_ref (the box at rest at T_ref): as s = g H / c^2 -> 0 the
  // pressure becomes uniform and this tends to the low-Mach twin's P / p0 (Le Quere et al. 2005).
  double pressure_ratio() const {
    return mean_pressure_ / (this->prm_.number_density * this->prm_.reference_temperature);
  }
  std::string state_note() const {
    std::ostringstream note;
    note << ", int n dV / N - 1 = " << mass_defect_ / total_particles_;
    return note.str();
  }

  // After the DoFs and constraints of a mesh: the anchor is the first density DoF that no
  // constraint ties (periodic faces, hanging nodes); beta ~ the integral of one basis function.
  void setup(const dealii::DoFHandler<dim>& dofs, const dealii::AffineConstraints<double>& c) {
    anchor_ = dealii::numbers::invalid_dof_index;
    const dealii::FEValuesExtractors::Scalar scalar(dim);
    for (const auto i : dealii::DoFTools::extract_dofs(dofs, dofs.get_fe().component_mask(scalar)))
      if (!c.is_constrained(i)) {
        anchor_ = i;
        break;
      }
    if (anchor_ == dealii::numbers::invalid_dof_index)
      throw std::logic_error("compressible: no free density DoF");
    anchor_weight_ = volume_ / dofs.get_triangulation().n_active_cells();
  }
  // int n dV - N of the state (the anchor's residual); throws std::runtime_error for n <= 0 or
  // T <= 0 at a quadrature point (Newton's line search then shortens the step).
  template <class VectorType>
  void begin_assembly(const dealii::DoFHandler<dim>& dofs, const VectorType& x, bool) {
    update_derived_state(dofs, x);
    anchor_assembled_ = false;
  }
  template <class VectorType>
  void update_derived_state(const dealii::DoFHandler<dim>& dofs, const VectorType& x) {
    dealii::FEValues<dim> fe_values(dofs.get_fe(), dealii::QGauss<dim>(3),
                                    dealii::update_values | dealii::update_JxW_values);
    const dealii::FEValuesExtractors::Scalar scalar(dim), temperature(dim + 1);
    std::vector<double> n(fe_values.n_quadrature_points), T(fe_values.n_quadrature_points);
    double mass = 0, pressure_integral = 0;
    for (const auto& cell : dofs.active_cell_iterators()) {
      fe_values.reinit(cell);
      fe_values[scalar].get_function_values(x, n);
      fe_values[temperature].get_function_values(x, T);
      for (unsigned q = 0; q < n.size(); ++q) {
        if (!(n[q] > 0) || !(T[q] > 0))
          throw std::runtime_error("compressible: n <= 0 or T <= 0 at a quadrature point");
        mass += n[q] * fe_values.JxW(q);
        pressure_integral +=
            pressure(this->prm_.equation_of_state, n[q], T[q]).p * fe_values.JxW(q);
      }
    }
    mass_defect_ = mass - total_particles_;
    mean_pressure_ = pressure_integral / volume_;
  }
  // The start holds exactly N particles. The interpolated column misses N by O(h^2), and in time
  // the mass equations keep d/dt int n dV = 0, so the anchor would pull that defect back only by
  // a0 / (a0 + 1) a step (summing the equations: (a0 + 1) int n = a0 int n_old + N).
  template <class VectorType>
  void normalise_initial_state(const dealii::DoFHandler<dim>& dofs, VectorType& x) {
    update_derived_state(dofs, x);
    const double scale = total_particles_ / (total_particles_ + mass_defect_);
    const dealii::FEValuesExtractors::Scalar scalar(dim);
    for (const auto i : dealii::DoFTools::extract_dofs(dofs, dofs.get_fe().component_mask(scalar)))
      x(i) *= scale; // int n_h dV is linear in the density DoFs; constraints stay satisfied
  }
  // The rank-one row: r - beta e_k (the matrix carries beta e_k e_k^T).
  template <class VectorType> void end_assembly(VectorType& row) const {
    row(anchor_) -= anchor_weight_;
  }

  // The cell integrals of the system at the top of this file: out.rhs = -R and, if asked,
  // out.matrix = dR/dx, out.column = e_k at the anchor, out.row(j) = int phi_n_j.
  template <class VectorType>
  void assemble_cell(const CellIterator<dim>& cell, const VectorType& x,
                     const AssemblyContext<dim, VectorType>& context, CellSystem& out);

  template <class VectorType>
  void finish_result(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                     const FlowIntegrals& flow, ContinuumResult& result) const;

  // For a manufactured solution (tests): f(x, t) with dim + 2 components added to the
  // right-hand sides of momentum, mass and energy (t: the time of the step's end; 0 steady),
  // and its exact state as the start in time.
  using Forcing = std::function<void(const dealii::Point<dim>&, double, dealii::Vector<double>&)>;
  void set_forcing(Forcing f) { forcing_ = std::move(f); }
  void set_initial_state(std::shared_ptr<dealii::Function<dim>> start) {
    start_ = std::move(start);
  }
  void begin_time_step(double time) { time_ = time; }

private:
  // One quadrature point's coefficients and the parts of the residual that no test function
  // changes (assemble_cell's q loop).
  struct PointTerms {
    PressureState s;
    PressureWork work;
    double eta = 0, deta = 0, deta_n = 0, kappa = 0, dkappa = 0, dkappa_n = 0;
    double lambda = 0, dlambda = 0; // tau's I part, zeta - (2/d) eta, and its d/dT
    double div_u = 0, dn_dt = 0, dT_dt = 0, heating = 0, source = 0;
    double heating_T = 0, heating_n = 0; // d(tau : grad u)/dT, /dn
    dealii::SymmetricTensor<2, dim> eps_u;
    dealii::Tensor<1, dim> du_dt, flux;
  };
  PointTerms point_terms(unsigned q, bool in_time, double a0) const;
  double residual(const PointTerms& t, unsigned q, unsigned i,
                  const dealii::Tensor<1, dim>& g) const;
  double jacobian(const PointTerms& t, unsigned q, unsigned i, unsigned j, bool in_time, double a0,
                  const dealii::Tensor<1, dim>& g) const;
  void add_forcing(unsigned i, double JxW, CellSystem& out);
  void add_anchor(const CellIterator<dim>& cell, bool with_jacobian, CellSystem& out);

  class InitialState : public dealii::Function<dim> {
  public:
    InitialState(const ContinuumParameters& prm, std::shared_ptr<dealii::Function<dim>> T,
                 std::shared_ptr<dealii::Function<dim>> given)
        : dealii::Function<dim>(dim + 2), prm_(prm), temperature_(std::move(T)),
          given_(std::move(given)) {}
    double value(const dealii::Point<dim>& p, unsigned component) const override {
      if (given_) return given_->value(p, component);
      if (component < dim) return 0.0;
      if (component == dim + 1) return temperature_->value(p, dim + 1);
      std::array<double, 3> x{{0, 0, 0}};
      for (int d = 0; d < dim; ++d) x[d] = p[d];
      return isothermal_column_density(prm_, prm_.reference_temperature, x);
    }

  private:
    const ContinuumParameters& prm_;
    std::shared_ptr<dealii::Function<dim>> temperature_, given_;
  };

  double volume_ = 0, total_particles_ = 0;
  double reference_flux_ = 0; // kappa(T_ref) |dT| / H
  CellValues<dim> values_;
  WallTerms<dim> walls_;
  double c_v_ = 0; // heat capacity per particle at constant volume
  dealii::types::global_dof_index anchor_ = 0;
  double anchor_weight_ = 1; // beta
  bool anchor_assembled_ = false;
  double mass_defect_ = 0;   // int n dV - N of the last assembled state
  double mean_pressure_ = 0; // (1/|Omega|) int p dV of the same state
  std::vector<dealii::Tensor<1, dim>> grad_n_, history_u_, grad_phi_n_;
  std::vector<double> history_n_, history_T_;
  std::vector<dealii::types::global_dof_index> dofs_;
  Forcing forcing_;
  std::shared_ptr<dealii::Function<dim>> start_; // a test's start in time, else InitialState's
  double time_ = 0;
  dealii::Vector<double> force_ = dealii::Vector<double>(dim + 2);
};

template <int dim>
typename CompressibleModel<dim>::PointTerms
CompressibleModel<dim>::point_terms(unsigned q, bool in_time, double a0) const {
  const auto& prm = this->prm_;
  const double T_ref = prm.reference_temperature, n_ref = prm.number_density;
  const double two_over_d = 2.0 / dim;
  const auto& [u, grad_u, n, T, grad_T] = values_.state;
  PointTerms t;
  t.s = pressure(prm.equation_of_state, n[q], T[q]);
  t.work = pressure_work(t.s, T[q]);
  // eta(n, T), kappa(n, T), and d/dT, d/dn for the Jacobian.
  const auto eta = prm.viscosity.at(n[q], T[q], n_ref, T_ref);
  const auto kappa = prm.conductivity.at(n[q], T[q], n_ref, T_ref);
  t.eta = eta.value, t.deta = eta.d_T, t.deta_n = eta.d_n;
  t.kappa = kappa.value, t.dkappa = kappa.d_T, t.dkappa_n = kappa.d_n;
  t.lambda = prm.bulk_viscosity - two_over_d * t.eta, t.dlambda = -two_over_d * t.deta;
  t.source = heat_source_density(prm, values_.point(q));
  t.eps_u = dealii::symmetrize(grad_u[q]);
  t.div_u = dealii::trace(grad_u[q]);
  // Material derivatives (steady: the advective parts only); BDF d/dt y ~ a0 y + history.
  t.du_dt = grad_u[q] * u[q];
  t.dT_dt = u[q] * grad_T[q];
  if (in_time) {
    t.du_dt += a0 * u[q] + history_u_[q];
    t.dn_dt = a0 * n[q] + history_n_[q];
    t.dT_dt += a0 * T[q] + history_T_[q];
  }
  t.flux = n[q] * u[q];                                                       // n u
  t.heating = 2 * t.eta * (t.eps_u * t.eps_u) + t.lambda * t.div_u * t.div_u; // tau : grad u
  t.heating_T = 2 * t.deta * (t.eps_u * t.eps_u) + t.dlambda * t.div_u * t.div_u;
  t.heating_n = t.deta_n * (2 * (t.eps_u * t.eps_u) - two_over_d * t.div_u * t.div_u);
  return t;
}

// Weak residual R (top of this file) at q against test function i: momentum against phi_u,
// mass against phi_n, energy against phi_T.
template <int dim>
double CompressibleModel<dim>::residual(const PointTerms& t, unsigned q, unsigned i,
                                        const dealii::Tensor<1, dim>& g) const {
  const double m = this->prm_.particle_mass;
  const auto& n = values_.state.s;
  const auto& grad_T = values_.state.grad_T;
  const auto& [phi_u, grad_phi_u, eps_phi_u, div_phi_u, phi_n, phi_T, grad_phi_T] = values_.shape;
  return m * n[q] * (t.du_dt * phi_u[i]) + 2 * t.eta * (t.eps_u * eps_phi_u[i]) +
         t.lambda * t.div_u * div_phi_u[i] - t.s.p * div_phi_u[i] - m * n[q] * (g * phi_u[i]) +
         phi_n[i] * t.dn_dt - grad_phi_n_[i] * t.flux +
         (n[q] * c_v_ * t.dT_dt + t.work.value * t.div_u - t.heating - t.source) * phi_T[i] +
         t.kappa * (grad_T[q] * grad_phi_T[i]);
}

// The exact derivative of residual(i) in direction (phi_u_j, phi_n_j, phi_T_j).
template <int dim>
double CompressibleModel<dim>::jacobian(const PointTerms& t, unsigned q, unsigned i, unsigned j,
                                        bool in_time, double a0,
                                        const dealii::Tensor<1, dim>& g) const {
  const double m = this->prm_.particle_mass, c_v = c_v_, two_over_d = 2.0 / dim;
  const auto& [u, grad_u, n, T, grad_T] = values_.state;
  const auto& [phi_u, grad_phi_u, eps_phi_u, div_phi_u, phi_n, phi_T, grad_phi_T] = values_.shape;
  const double stress_u_i = 2 * (t.eps_u * eps_phi_u[i]) - two_over_d * t.div_u * div_phi_u[i];
  const double div_j = div_phi_u[j];
  dealii::Tensor<1, dim> ddu_dt = grad_phi_u[j] * u[q] + grad_u[q] * phi_u[j];
  double ddT_dt = phi_u[j] * grad_T[q] + u[q] * grad_phi_T[j];
  if (in_time) ddu_dt += a0 * phi_u[j], ddT_dt += a0 * phi_T[j];
  const double dn_j = phi_n[j], dT_j = phi_T[j];
  const double momentum =
      m * dn_j * (t.du_dt * phi_u[i]) + m * n[q] * (ddu_dt * phi_u[i]) +
      2 * t.eta * (eps_phi_u[j] * eps_phi_u[i]) + t.lambda * div_j * div_phi_u[i] +
      (dT_j * t.deta + dn_j * t.deta_n) * stress_u_i -
      (t.s.p_n * dn_j + t.s.p_T * dT_j) * div_phi_u[i] - m * dn_j * (g * phi_u[i]);
  const double mass =
      (in_time ? a0 * dn_j * phi_n[i] : 0.0) - grad_phi_n_[i] * (dn_j * u[q] + n[q] * phi_u[j]);
  const double dheating = 4 * t.eta * (t.eps_u * eps_phi_u[j]) + 2 * t.lambda * t.div_u * div_j +
                          t.heating_T * dT_j + t.heating_n * dn_j;
  const double energy =
      (dn_j * c_v * t.dT_dt + n[q] * c_v * ddT_dt +
       (t.work.d_n * dn_j + t.work.d_T * dT_j) * t.div_u + t.work.value * div_j - dheating) *
          phi_T[i] +
      t.kappa * (grad_phi_T[j] * grad_phi_T[i]) +
      (t.dkappa * dT_j + t.dkappa_n * dn_j) * (grad_T[q] * grad_phi_T[i]);
  return momentum + mass + energy;
}

// A manufactured solution's f(x, t) at the point (set_forcing; force_) against test function i.
template <int dim>
void CompressibleModel<dim>::add_forcing(unsigned i, double JxW, CellSystem& out) {
  const auto& [phi_u, grad_phi_u, eps_phi_u, div_phi_u, phi_n, phi_T, grad_phi_T] = values_.shape;
  dealii::Tensor<1, dim> f_u;
  for (int d = 0; d < dim; ++d) f_u[d] = force_(d);
  out.rhs(i) += (f_u * phi_u[i] + force_(dim) * phi_n[i] + force_(dim + 1) * phi_T[i]) * JxW;
}

// The anchor: + (int n dV - N) in its mass equation, once (the first cell that holds it).
template <int dim>
void CompressibleModel<dim>::add_anchor(const CellIterator<dim>& cell, bool with_jacobian,
                                        CellSystem& out) {
  if (anchor_assembled_) return;
  cell->get_dof_indices(dofs_);
  for (unsigned i = 0; i < values_.n; ++i)
    if (dofs_[i] == anchor_) {
      out.rhs(i) -= mass_defect_;
      if (with_jacobian) {
        out.column(i) += 1.0;
        out.matrix(i, i) += anchor_weight_;
      }
      anchor_assembled_ = true;
      break;
    }
}

template <int dim>
template <class VectorType>
void CompressibleModel<dim>::assemble_cell(const CellIterator<dim>& cell, const VectorType& x,
                                           const AssemblyContext<dim, VectorType>& context,
                                           CellSystem& out) {
  auto& v = values_;
  v.reinit(cell, x);
  v.fe_values[v.scalar].get_function_gradients(x, grad_n_);
  const bool in_time = context.history != nullptr, with_jacobian = context.with_jacobian;
  const double a0 = context.a0;
  if (in_time) {
    v.values_of(*context.history, history_u_, history_T_);
    v.fe_values[v.scalar].get_function_values(*context.history, history_n_);
  }
  grad_phi_n_.resize(v.n);
  for (unsigned q = 0; q < v.n_q; ++q) {
    const PointTerms t = point_terms(q, in_time, a0);
    const double JxW = v.fe_values.JxW(q);
    if (forcing_) forcing_(v.fe_values.quadrature_point(q), time_, force_);
    v.shape_functions(q);
    for (unsigned k = 0; k < v.n; ++k) grad_phi_n_[k] = v.fe_values[v.scalar].gradient(k, q);
    for (unsigned i = 0; i < v.n; ++i) {
      out.rhs(i) -= residual(t, q, i, context.gravity) * JxW;
      if (forcing_) add_forcing(i, JxW, out);
      if (!with_jacobian) continue;
      out.row(i) += v.shape.phi_s[i] * JxW; // d(int n dV)/dx_i
      for (unsigned j = 0; j < v.n; ++j)
        out.matrix(i, j) += jacobian(t, q, i, j, in_time, a0, context.gravity) * JxW;
    }
  }
  walls_.add(cell, x, with_jacobian, out);
  add_anchor(cell, with_jacobian, out);
}

template <int dim>
template <class VectorType>
void CompressibleModel<dim>::finish_result(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                                           const FlowIntegrals& flow,
                                           ContinuumResult& result) const {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const auto i : dealii::DoFTools::extract_dofs(
           dofs, dofs.get_fe().component_mask(dealii::FEValuesExtractors::Scalar(dim)))) {
    lo = std::min(lo, x[i]);
    hi = std::max(hi, x[i]);
  }
  result.density_min = lo, result.density_max = hi;
  result.mass_error = flow.particles / total_particles_ - 1.0;
  result.pressure_ratio = pressure_ratio();
}

template <int dim>
using CompressibleProblem = FlowProblem<dim, CompressibleModel<dim>, SerialBackend<dim>>;
extern template class FlowProblem<2, CompressibleModel<2>, SerialBackend<2>>;
extern template class FlowProblem<3, CompressibleModel<3>, SerialBackend<3>>;

} // namespace twinflow::continuum
