#pragma once
// Boussinesq natural convection, a model of FlowProblem (flow_problem.hpp): its cell residual and
// exact Jacobian. Oberbeck-Boussinesq equations in the particle units (step-31 for Stokes +
// heat, with the inertial term of step-57), unknowns (u, p, T):
//   n m (du/dt + (u . grad) u) - div(2 eta(T) eps(u)) + grad p = -n m alpha (T - T_ref) g
//   div u = 0
//   n c_p (dT/dt + u . grad T) - div(kappa(T) grad T) = Q
// eps(u) the symmetric gradient; flux, Kapitza and Navier walls: WallTerms (flow_model.hpp).
// Residual R and its exact Jacobian (Gateaux derivative) for Newton's method. Steady: no time
// derivatives. In time, a multistep (BDF) derivative d/dt x ~ a0 x + h with the history
// h = sum_k a_k x^{n+1-k} of the earlier steps (BDF2: a0 = 3/(2 dt), h = (-4 x^n + x^{n-1})/(2 dt);
// Hairer, Norsett & Wanner I, sec. III.1).
//
// BoussinesqProblem<dim>: serial and direct (dim = 2: flow_2d.cpp; 3: flow_3d.cpp, thin boxes
// such as one periodic in z); the distributed solver: boussinesq_distributed.hpp.

#include "continuum/backend_serial.hpp"
#include "continuum/flow_model.hpp"
#include "continuum/flow_problem.hpp"

namespace twinflow::continuum {

template <int dim> class BoussinesqModel : public FlowModel<dim> {
public:
  static constexpr const char* name = "boussinesq";
  static constexpr bool divergence_free = true;

  BoussinesqModel(const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
                  const dealii::FiniteElement<dim>& fe)
      : FlowModel<dim>(prm, numbers), values_(fe, dealii::QGauss<dim>(3)), walls_(fe, prm),
        history_u_(values_.n_q), history_T_(values_.n_q) {}

  // No pressure-pressure or pressure-temperature blocks.
  dealii::Table<2, dealii::DoFTools::Coupling> coupling() const {
    const unsigned p = dim, t = dim + 1;
    dealii::Table<2, dealii::DoFTools::Coupling> coupling(dim + 2, dim + 2);
    for (unsigned c = 0; c < dim + 2; ++c)
      for (unsigned d = 0; d < dim + 2; ++d)
        coupling[c][d] = ((c == p && (d == p || d == t)) || (c == t && d == p))
                             ? dealii::DoFTools::none
                             : dealii::DoFTools::always;
    return coupling;
  }

  // cell.rhs = -R (and cell.matrix = dR/dx if with_jacobian) at the state x with the context's
  // gravity; with a history, the time derivatives a0 x + history are included.
  template <class VectorType>
  void assemble_cell(const CellIterator<dim>& cell, const VectorType& x,
                     const AssemblyContext<dim, VectorType>& context, CellSystem& out) {
    auto& v = values_;
    v.reinit(cell, x);
    const auto& prm = this->prm_;
    const double rho = prm.mass_density(), ncp = prm.heat_capacity_per_volume();
    const double alpha = prm.thermal_expansion, T_ref = prm.reference_temperature;
    const auto& [u, grad_u, p, T, grad_T] = v.state;
    const auto& [phi_u, grad_phi_u, eps_phi_u, div_phi_u, phi_p, phi_T, grad_phi_T] = v.shape;
    if (context.history) v.values_of(*context.history, history_u_, history_T_);
    const double a0 = context.a0;
    const dealii::Tensor<1, dim>& g = context.gravity;
    for (unsigned q = 0; q < v.n_q; ++q) {
      const double eta = prm.viscosity.at(T[q], T_ref);
      const double deta = prm.viscosity.derivative(T[q], T_ref);
      const double kappa = prm.conductivity.at(T[q], T_ref);
      const double dkappa = prm.conductivity.derivative(T[q], T_ref);
      const double source = heat_source_density(prm, v.point(q));
      // Boussinesq buoyancy, rho(T) g with rho = n m (1 - alpha (T - T_ref)); constant part in p.
      const dealii::Tensor<1, dim> buoyancy = -rho * alpha * (T[q] - T_ref) * g;
      const dealii::SymmetricTensor<2, dim> eps_u = dealii::symmetrize(grad_u[q]);
      const double div_u = dealii::trace(grad_u[q]);
      const dealii::Tensor<1, dim> advection = grad_u[q] * u[q]; // (u . grad) u
      dealii::Tensor<1, dim> du_dt;
      double dT_dt = 0;
      if (context.history) time_derivatives(q, a0, u[q], T[q], du_dt, dT_dt);
      const double JxW = v.fe_values.JxW(q);
      v.shape_functions(q);
      for (unsigned i = 0; i < v.n; ++i) {
        // Weak residual of momentum, continuity, energy (equations at the top of this file).
        const double residual = rho * (du_dt + advection) * phi_u[i] +
                                2 * eta * (eps_u * eps_phi_u[i]) - p[q] * div_phi_u[i] -
                                buoyancy * phi_u[i] - phi_p[i] * div_u +
                                ncp * (dT_dt + u[q] * grad_T[q]) * phi_T[i] +
                                kappa * (grad_T[q] * grad_phi_T[i]) - source * phi_T[i];
        out.rhs(i) -= residual * JxW;
        if (!context.with_jacobian) continue;
        for (unsigned j = 0; j < v.n; ++j) {
          // Exact derivative of the residual above in direction (phi_u_j, phi_p_j, phi_T_j).
          const double jacobian =
              rho * (a0 * phi_u[j] + grad_phi_u[j] * u[q] + grad_u[q] * phi_u[j]) * phi_u[i] +
              2 * eta * (eps_phi_u[j] * eps_phi_u[i]) +
              2 * deta * phi_T[j] * (eps_u * eps_phi_u[i]) - phi_p[j] * div_phi_u[i] +
              rho * alpha * phi_T[j] * (g * phi_u[i]) - phi_p[i] * div_phi_u[j] +
              ncp * (a0 * phi_T[j] + phi_u[j] * grad_T[q] + u[q] * grad_phi_T[j]) * phi_T[i] +
              kappa * (grad_phi_T[j] * grad_phi_T[i]) +
              dkappa * phi_T[j] * (grad_T[q] * grad_phi_T[i]);
          out.matrix(i, j) += jacobian * JxW;
        }
      }
    }
    walls_.add(cell, x, context.with_jacobian, out);
  }

private:
  // Time derivatives at point q (zero when steady): du/dt ~ a0 u + h_u, dT/dt ~ a0 T + h_T.
  void time_derivatives(unsigned q, double a0, const dealii::Tensor<1, dim>& u, double T,
                        dealii::Tensor<1, dim>& du_dt, double& dT_dt) const {
    du_dt = a0 * u + history_u_[q];
    dT_dt = a0 * T + history_T_[q];
  }

  CellValues<dim> values_;
  WallTerms<dim> walls_;
  std::vector<dealii::Tensor<1, dim>> history_u_;
  std::vector<double> history_T_;
};

template <int dim>
using BoussinesqProblem = FlowProblem<dim, BoussinesqModel<dim>, SerialBackend<dim>>;
extern template class FlowProblem<2, BoussinesqModel<2>, SerialBackend<2>>;
extern template class FlowProblem<3, BoussinesqModel<3>, SerialBackend<3>>;

} // namespace twinflow::continuum
