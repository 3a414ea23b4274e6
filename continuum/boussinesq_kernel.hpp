#pragma once
// The cell integrals of the steady Boussinesq system (one place for the serial and the
// distributed solver). Oberbeck-Boussinesq equations in the particle units (step-31 for
// Stokes + heat, with the inertial term of step-57), unknowns (u, p, T):
//   n m (du/dt + (u . grad) u) - div(2 eta(T) eps(u)) + grad p = -n m alpha (T - T_ref) g
//   div u = 0
//   n c_p (dT/dt + u . grad T) - div(kappa(T) grad T) = Q
// eps(u) the symmetric gradient; flux walls add - int_Gamma q phi_T, Kapitza (Robin) walls
// - int_Gamma h_K (T_wall - T) phi_T (Kapitza 1941: a jump T_wall - T = q / h_K at the wall), or
// its inverse law h_K T_wall^2 (1/T - 1/T_wall) (DirectionBoundary::kapitza_flux); Navier
// walls + int_Gamma (eta(T) / b) u . phi_u (the normal part is constrained to zero).
// Residual R and its exact
// Jacobian (Gateaux derivative) for Newton's method. Steady: no time derivatives. In time, a
// multistep (BDF) derivative d/dt x ~ a0 x + h with the history h = sum_k a_k x^{n+1-k} of the
// earlier steps (BDF2: a0 = 3/(2 dt), h = (-4 x^n + x^{n-1})/(2 dt); Hairer, Norsett & Wanner I,
// sec. III.1).

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "continuum/parameters.hpp"

namespace twinflow::continuum {

template <int dim> class BoussinesqCellKernel {
public:
  BoussinesqCellKernel(const dealii::FiniteElement<dim>& fe, const ContinuumParameters& prm)
      : prm_(prm), quadrature_(3), face_quadrature_(3),
        fe_values_(fe, quadrature_,
                   dealii::update_values | dealii::update_gradients |
                       dealii::update_quadrature_points | dealii::update_JxW_values),
        fe_face_values_(fe, face_quadrature_, dealii::update_values | dealii::update_JxW_values),
        n_(fe.n_dofs_per_cell()), u_(quadrature_.size()), grad_T_(quadrature_.size()),
        grad_u_(quadrature_.size()), p_(quadrature_.size()), T_(quadrature_.size()),
        history_u_(quadrature_.size()), history_T_(quadrature_.size()),
        face_T_(face_quadrature_.size()), face_u_(face_quadrature_.size()), phi_u_(n_),
        grad_phi_T_(n_), grad_phi_u_(n_), eps_phi_u_(n_), div_phi_u_(n_), phi_p_(n_), phi_T_(n_) {}

  // cell_rhs = -R (and cell_matrix = dR/dx if with_jacobian) at the state x, gravity scaled by
  // gravity_factor; with a `history`, the time derivatives a0 x + history are included.
  template <class VectorType>
  void assemble(const typename dealii::DoFHandler<dim>::active_cell_iterator& cell,
                const VectorType& x, bool with_jacobian, double gravity_factor,
                dealii::FullMatrix<double>& cell_matrix, dealii::Vector<double>& cell_rhs,
                double a0 = 0.0, const VectorType* history = nullptr) {
    const dealii::FEValuesExtractors::Vector velocities(0);
    const dealii::FEValuesExtractors::Scalar pressure(dim), temperature(dim + 1);
    auto& fv = fe_values_;
    fv.reinit(cell);
    cell_matrix = 0;
    cell_rhs = 0;
    fv[velocities].get_function_values(x, u_);
    fv[velocities].get_function_gradients(x, grad_u_);
    fv[pressure].get_function_values(x, p_);
    fv[temperature].get_function_values(x, T_);
    fv[temperature].get_function_gradients(x, grad_T_);
    if (history) {
      fv[velocities].get_function_values(*history, history_u_);
      fv[temperature].get_function_values(*history, history_T_);
    }
    const double rho = prm_.mass_density(), ncp = prm_.heat_capacity_per_volume();
    const double alpha = prm_.thermal_expansion, T_ref = prm_.reference_temperature;
    dealii::Tensor<1, dim> g;
    for (int d = 0; d < dim; ++d) g[d] = gravity_factor * prm_.gravity[d];
    for (unsigned q = 0; q < quadrature_.size(); ++q) {
      const double eta = prm_.viscosity.at(T_[q], T_ref);
      const double deta = prm_.viscosity.derivative(T_[q], T_ref);
      const double kappa = prm_.conductivity.at(T_[q], T_ref);
      const double dkappa = prm_.conductivity.derivative(T_[q], T_ref);
      std::array<double, 3> x3{{0, 0, 0}};
      for (int d = 0; d < dim; ++d) x3[d] = fv.quadrature_point(q)[d];
      const double source = heat_source_density(prm_, x3);
      // Boussinesq buoyancy, rho(T) g with rho = n m (1 - alpha (T - T_ref)); constant part in p.
      const dealii::Tensor<1, dim> buoyancy = -rho * alpha * (T_[q] - T_ref) * g;
      const dealii::SymmetricTensor<2, dim> eps_u = dealii::symmetrize(grad_u_[q]);
      const double div_u = dealii::trace(grad_u_[q]);
      const dealii::Tensor<1, dim> advection = grad_u_[q] * u_[q]; // (u . grad) u
      // Time derivatives (zero when steady): du/dt ~ a0 u + h_u, dT/dt ~ a0 T + h_T.
      dealii::Tensor<1, dim> du_dt;
      double dT_dt = 0;
      if (history) {
        du_dt = a0 * u_[q] + history_u_[q];
        dT_dt = a0 * T_[q] + history_T_[q];
      }
      const double JxW = fv.JxW(q);
      for (unsigned k = 0; k < n_; ++k) {
        phi_u_[k] = fv[velocities].value(k, q);
        grad_phi_u_[k] = fv[velocities].gradient(k, q);
        eps_phi_u_[k] = fv[velocities].symmetric_gradient(k, q);
        div_phi_u_[k] = fv[velocities].divergence(k, q);
        phi_p_[k] = fv[pressure].value(k, q);
        phi_T_[k] = fv[temperature].value(k, q);
        grad_phi_T_[k] = fv[temperature].gradient(k, q);
      }
      for (unsigned i = 0; i < n_; ++i) {
        // Weak residual of momentum, continuity, energy (equations at the top of this file).
        const double residual = rho * (du_dt + advection) * phi_u_[i] +
                                2 * eta * (eps_u * eps_phi_u_[i]) - p_[q] * div_phi_u_[i] -
                                buoyancy * phi_u_[i] - phi_p_[i] * div_u +
                                ncp * (dT_dt + u_[q] * grad_T_[q]) * phi_T_[i] +
                                kappa * (grad_T_[q] * grad_phi_T_[i]) - source * phi_T_[i];
        cell_rhs(i) -= residual * JxW;
        if (!with_jacobian) continue;
        for (unsigned j = 0; j < n_; ++j) {
          // Exact derivative of the residual above in direction (phi_u_j, phi_p_j, phi_T_j).
          const double jacobian =
              rho * (a0 * phi_u_[j] + grad_phi_u_[j] * u_[q] + grad_u_[q] * phi_u_[j]) * phi_u_[i] +
              2 * eta * (eps_phi_u_[j] * eps_phi_u_[i]) +
              2 * deta * phi_T_[j] * (eps_u * eps_phi_u_[i]) - phi_p_[j] * div_phi_u_[i] +
              rho * alpha * phi_T_[j] * (g * phi_u_[i]) - phi_p_[i] * div_phi_u_[j] +
              ncp * (a0 * phi_T_[j] + phi_u_[j] * grad_T_[q] + u_[q] * grad_phi_T_[j]) * phi_T_[i] +
              kappa * (grad_phi_T_[j] * grad_phi_T_[i]) +
              dkappa * phi_T_[j] * (grad_T_[q] * grad_phi_T_[i]);
          cell_matrix(i, j) += jacobian * JxW;
        }
      }
    }
    // Heat flux into the domain through flux walls, - int_Gamma q phi_T, and through Kapitza
    // walls, q(T) with its Jacobian -q'(T) phi_T,j phi_T,i.
    for (const auto& face : cell->face_iterators()) {
      if (!face->at_boundary()) continue;
      const int d = face->boundary_id() / 2, side = face->boundary_id() % 2;
      const auto& b = prm_.boundary[d];
      if (b.periodic) continue;
      const bool robin = b.robin(side);
      if (b.navier(side))
        add_navier_traction(cell, face, x, b.slip_length[side], with_jacobian, cell_matrix,
                            cell_rhs);
      if (!robin && (b.fixed_temperature[side] || b.heat_flux[side] == 0.0)) continue;
      fe_face_values_.reinit(cell, face);
      if (robin) fe_face_values_[temperature].get_function_values(x, face_T_);
      for (unsigned q = 0; q < face_quadrature_.size(); ++q) {
        const double JxW = fe_face_values_.JxW(q);
        const double flux_in = robin ? b.kapitza_flux(side, face_T_[q]) : b.heat_flux[side];
        const double dflux = robin ? b.kapitza_flux_derivative(side, face_T_[q]) : 0.0;
        for (unsigned i = 0; i < n_; ++i) {
          const double phi_i = fe_face_values_[temperature].value(i, q);
          cell_rhs(i) += flux_in * phi_i * JxW;
          if (robin && with_jacobian)
            for (unsigned j = 0; j < n_; ++j)
              cell_matrix(i, j) -= dflux * fe_face_values_[temperature].value(j, q) * phi_i * JxW;
        }
      }
    }
  }

private:
  // Navier wall: residual + int (eta(T)/b) u . phi_u,i; Jacobian (eta/b) phi_u,j . phi_u,i +
  // (eta'(T)/b) phi_T,j u . phi_u,i.
  template <class Face, class VectorType>
  void add_navier_traction(const typename dealii::DoFHandler<dim>::active_cell_iterator& cell,
                           const Face& face, const VectorType& x, double slip_length,
                           bool with_jacobian, dealii::FullMatrix<double>& cell_matrix,
                           dealii::Vector<double>& cell_rhs) {
    const dealii::FEValuesExtractors::Vector velocities(0);
    const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
    fe_face_values_.reinit(cell, face);
    fe_face_values_[temperature].get_function_values(x, face_T_);
    fe_face_values_[velocities].get_function_values(x, face_u_);
    const double T_ref = prm_.reference_temperature;
    for (unsigned q = 0; q < face_quadrature_.size(); ++q) {
      const double JxW = fe_face_values_.JxW(q);
      // Navier (1823): the wall's traction eta u_t / b, its friction per area eta / b
      const double friction = prm_.viscosity.at(face_T_[q], T_ref) / slip_length;
      const double dfriction = prm_.viscosity.derivative(face_T_[q], T_ref) / slip_length;
      for (unsigned i = 0; i < n_; ++i) {
        const dealii::Tensor<1, dim> phi_i = fe_face_values_[velocities].value(i, q);
        cell_rhs(i) -= friction * (face_u_[q] * phi_i) * JxW;
        if (!with_jacobian) continue;
        for (unsigned j = 0; j < n_; ++j)
          cell_matrix(i, j) +=
              (friction * (fe_face_values_[velocities].value(j, q) * phi_i) +
               dfriction * fe_face_values_[temperature].value(j, q) * (face_u_[q] * phi_i)) *
              JxW;
      }
    }
  }

  const ContinuumParameters& prm_;
  const dealii::QGauss<dim> quadrature_;
  const dealii::QGauss<dim - 1> face_quadrature_;
  dealii::FEValues<dim> fe_values_;
  dealii::FEFaceValues<dim> fe_face_values_;
  const unsigned n_;
  std::vector<dealii::Tensor<1, dim>> u_, grad_T_;
  std::vector<dealii::Tensor<2, dim>> grad_u_;
  std::vector<double> p_, T_;
  std::vector<dealii::Tensor<1, dim>> history_u_;
  std::vector<double> history_T_, face_T_;
  std::vector<dealii::Tensor<1, dim>> face_u_;
  std::vector<dealii::Tensor<1, dim>> phi_u_, grad_phi_T_;
  std::vector<dealii::Tensor<2, dim>> grad_phi_u_;
  std::vector<dealii::SymmetricTensor<2, dim>> eps_phi_u_;
  std::vector<double> div_phi_u_, phi_p_, phi_T_;
};

} // namespace twinflow::continuum
