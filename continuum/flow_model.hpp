#pragma once
// What a flow model gives FlowProblem (flow_problem.hpp), and the pieces models share.
//
// Unknowns (u_0..u_{dim-1}, s, T): velocity (Q2), one scalar s (Q1 by default: the pressure of
// Boussinesq and low-Mach; the compressible model's number density, with gauge_pressure = false,
// scalar_name "n" and density(s, T) = s, compressible.hpp), temperature (Q2). A model is a class
// derived from FlowModel<dim> that defines
//   static constexpr const char* name;          // "boussinesq", ContinuumResult::model
//   std::unique_ptr<dealii::Function<dim>> initial_state() const;  (or keeps FlowModel's)
//   template <class VectorType>
//   void assemble_cell(cell, const VectorType& x, const AssemblyContext<dim, VectorType>&,
//   CellSystem&);
// the weak residual -R of the cell at the state x and, if asked, its Jacobian dR/dx. Everything
// else has a default here that a model may hide with its own member of the same name (no virtual
// calls: FlowProblem is a template over the model). Newton, continuation in Ra, the mesh levels,
// the march in time, Nu, wall Nu, mid-line maxima, bins and fields are FlowProblem's.

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/table.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum {

// What an assembly needs besides the state: whether to build the Jacobian, the gravity (scaled
// in the continuation: the Ra of this solve over the target Ra) and, in time, the BDF step
// (time_schedule.hpp): d/dt y ~ a0 y(x) + c[0] y(x^n) + c[1] y(x^{n-1}) for any function y of the
// state, `history` = c[0] x^n + c[1] x^{n-1} for y = x, `previous` = x^n, `older` = x^{n-1}.
// Steady: a0 = 0 and null pointers.
template <int dim, class VectorType> struct AssemblyContext {
  bool with_jacobian = true;
  dealii::Tensor<1, dim> gravity;
  double a0 = 0.0;
  std::array<double, 2> c{{0.0, 0.0}};
  const VectorType* history = nullptr;
  const VectorType* previous = nullptr;
  const VectorType* older = nullptr;
};

// A cell's share of the Newton system, zeroed by FlowProblem; the model adds its integrals:
// rhs = -R, matrix = dR/dx. A model with a global scalar g (global_scalar = true; low-Mach: the
// thermodynamic pressure P(x)) adds the rank-one term (dR/dg)(dg/dx)^T: `column` = dR/dg
// (condensed like the residual), `row` = its share of dg/dx (added raw; the model scales the sum
// in end_assembly).
struct CellSystem {
  explicit CellSystem(unsigned n) : matrix(n, n), rhs(n), column(n), row(n) {}
  dealii::FullMatrix<double> matrix;
  dealii::Vector<double> rhs, column, row;
};

// Integrals over the box for the results and the time series (flow_postprocess.templates.hpp).
struct FlowIntegrals {
  double nusselt = 0;          // volume form, 0 without a heated direction
  double kinetic_energy = 0;   // int (1/2) n m |u|^2 dV
  double max_speed = 0;        // max |u| at the quadrature points / (chi/H)
  double temperature_mean = 0; // (1/|Omega|) int T dV
  double particles = 0;        // int n dV
};

// A field computed from the components at a point (low-Mach: n(P, T)), for bins and output.
struct NamedField {
  std::string name;
  std::function<double(const dealii::Vector<double>& components)> value;
};

template <int dim> using CellIterator = typename dealii::DoFHandler<dim>::active_cell_iterator;

namespace detail {
// Wall Nu from the consistent (residual) flux, per wall of the heated direction; defined in
// flow_postprocess.templates.hpp.
template <int dim, class Model>
std::vector<double>
consistent_wall_nusselt(const dealii::DoFHandler<dim>& dofs, const dealii::Vector<double>& x,
                        const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
                        const Model& model);
} // namespace detail

template <int dim> class FlowModel {
public:
  static constexpr int time_order = 2;           // BDF2 (first step BDF1); 1: implicit Euler
  static constexpr bool divergence_free = false; // div u = 0: a stream function exists
  static constexpr bool gauge_pressure = true;   // s is a pressure known up to a constant
  static constexpr bool global_scalar = false;   // a rank-one term in the Jacobian (CellSystem)
  static constexpr unsigned scalar_degree = 1;   // of s (Taylor-Hood)
  static constexpr const char* scalar_name = "p";

  FlowModel(const ContinuumParameters& prm, const DimensionlessNumbers& numbers)
      : prm_(prm), numbers_(numbers) {}

  // Which component blocks of the Jacobian couple (sparsity pattern): all by default.
  dealii::Table<2, dealii::DoFTools::Coupling> coupling() const {
    dealii::Table<2, dealii::DoFTools::Coupling> table(dim + 2, dim + 2);
    table.fill(dealii::DoFTools::always);
    return table;
  }

  // At rest; T from the case's expression, else the conduction profile between the walls of the
  // heated direction (T_ref without one). Defined in flow_problem.templates.hpp.
  std::unique_ptr<dealii::Function<dim>> initial_state() const;
  // The interpolated start made to hold a constraint exactly (compressible: the particle count).
  template <class VectorType>
  void normalise_initial_state(const dealii::DoFHandler<dim>& /*dofs*/, VectorType& /*x*/) const {}

  std::vector<NamedField> derived_fields() const { return {}; }
  // The number density at a point from s and T (the heat capacity per volume is c_p n).
  double density(double /*s*/, double /*T*/) const { return prm_.number_density; }
  // kappa at a point from s and T (the compressible twin's also depends on n).
  double conductivity(double /*s*/, double T) const {
    return prm_.conductivity.at(T, prm_.reference_temperature);
  }
  // The heat flux per area that makes Nu (signed: Nu > 0 for heat from the lower to the upper
  // wall of the heated direction).
  double nusselt_flux_scale() const { return numbers_.conduction_flux; }
  double pressure_ratio() const { return 0.0; } // MeshLevel::pressure_ratio
  std::string state_note() const { return ""; } // appended to the progress lines

  // Hooks of the solver, no-ops here: after the DoFs and constraints of a mesh (compressible:
  // the anchor DoF of the particle count); quantities derived from a whole state (low-Mach: P from
  // the mass of the box); before an assembly (may throw std::runtime_error for a state outside the
  // model's range: Newton's line search then tries a shorter step); after it, with the summed
  // rank-one row; at the start of a step in time; model-specific results.
  void setup(const dealii::DoFHandler<dim>&, const dealii::AffineConstraints<double>&) {}
  template <class VectorType>
  void update_derived_state(const dealii::DoFHandler<dim>&, const VectorType&) {}
  template <class VectorType>
  void begin_assembly(const dealii::DoFHandler<dim>&, const VectorType&, bool /*with_jacobian*/) {}
  template <class VectorType> void end_assembly(VectorType& /*row*/) const {}
  void begin_time_step(double /*time at the step's end*/) {}
  template <class VectorType>
  void finish_result(const dealii::DoFHandler<dim>&, const VectorType&, const FlowIntegrals&,
                     ContinuumResult&) const {}

protected:
  // The state at rest with temperature `T(x)` (component dim + 1 of dim + 2).
  template <class F> static std::unique_ptr<dealii::Function<dim>> at_rest(F T) {
    return std::make_unique<dealii::VectorFunctionFromScalarFunctionObject<dim>>(
        std::function<double(const dealii::Point<dim>&)>(T), dim + 1, dim + 2);
  }
  double conduction_profile(const dealii::Point<dim>& x) const;

  const ContinuumParameters& prm_;
  const DimensionlessNumbers& numbers_;
};

// Values at the quadrature points of a cell (u, grad u, s, T, grad T of a state) and, per point,
// the shape functions of the Taylor-Hood element (the same for every model's kernel). A kernel
// names them with structured bindings: const auto& [u, grad_u, p, T, grad_T] = values.state.
template <int dim> struct CellValues {
  struct State {
    std::vector<dealii::Tensor<1, dim>> u;
    std::vector<dealii::Tensor<2, dim>> grad_u;
    std::vector<double> s, T;
    std::vector<dealii::Tensor<1, dim>> grad_T;
  };
  struct Shapes {
    std::vector<dealii::Tensor<1, dim>> phi_u;
    std::vector<dealii::Tensor<2, dim>> grad_phi_u;
    std::vector<dealii::SymmetricTensor<2, dim>> eps_phi_u;
    std::vector<double> div_phi_u, phi_s, phi_T;
    std::vector<dealii::Tensor<1, dim>> grad_phi_T;
  };

  CellValues(const dealii::FiniteElement<dim>& fe, const dealii::Quadrature<dim>& quadrature)
      : fe_values(fe, quadrature,
                  dealii::update_values | dealii::update_gradients |
                      dealii::update_quadrature_points | dealii::update_JxW_values),
        n(fe.n_dofs_per_cell()),
        n_q(quadrature.size()), state{std::vector<dealii::Tensor<1, dim>>(n_q),
                                      std::vector<dealii::Tensor<2, dim>>(n_q),
                                      std::vector<double>(n_q), std::vector<double>(n_q),
                                      std::vector<dealii::Tensor<1, dim>>(n_q)},
        shape{std::vector<dealii::Tensor<1, dim>>(n),
              std::vector<dealii::Tensor<2, dim>>(n),
              std::vector<dealii::SymmetricTensor<2, dim>>(n),
              std::vector<double>(n),
              std::vector<double>(n),
              std::vector<double>(n),
              std::vector<dealii::Tensor<1, dim>>(n)} {}

  template <class VectorType> void reinit(const CellIterator<dim>& cell, const VectorType& x) {
    fe_values.reinit(cell);
    fe_values[velocities].get_function_values(x, state.u);
    fe_values[velocities].get_function_gradients(x, state.grad_u);
    fe_values[scalar].get_function_values(x, state.s);
    fe_values[temperature].get_function_values(x, state.T);
    fe_values[temperature].get_function_gradients(x, state.grad_T);
  }
  // u and T of another vector on the same cell (time history).
  template <class VectorType>
  void values_of(const VectorType& y, std::vector<dealii::Tensor<1, dim>>& u_y,
                 std::vector<double>& T_y) const {
    fe_values[velocities].get_function_values(y, u_y);
    fe_values[temperature].get_function_values(y, T_y);
  }
  void shape_functions(unsigned q) {
    for (unsigned k = 0; k < n; ++k) {
      shape.phi_u[k] = fe_values[velocities].value(k, q);
      shape.grad_phi_u[k] = fe_values[velocities].gradient(k, q);
      shape.eps_phi_u[k] = fe_values[velocities].symmetric_gradient(k, q);
      shape.div_phi_u[k] = fe_values[velocities].divergence(k, q);
      shape.phi_s[k] = fe_values[scalar].value(k, q);
      shape.phi_T[k] = fe_values[temperature].value(k, q);
      shape.grad_phi_T[k] = fe_values[temperature].gradient(k, q);
    }
  }
  std::array<double, 3> point(unsigned q) const {
    std::array<double, 3> x{{0, 0, 0}};
    for (int d = 0; d < dim; ++d) x[d] = fe_values.quadrature_point(q)[d];
    return x;
  }

  const dealii::FEValuesExtractors::Vector velocities{0};
  const dealii::FEValuesExtractors::Scalar scalar{dim}, temperature{dim + 1};
  dealii::FEValues<dim> fe_values;
  const unsigned n, n_q; // shape functions, quadrature points
  State state;           // at the quadrature points
  Shapes shape;          // at the point of the last shape_functions(q)
};

// The wall integrals every model shares: heat flux walls, - int_Gamma q phi_T; Kapitza (Robin)
// walls, q(T) = h_K (T_wall - T) or its inverse law (DirectionBoundary::kapitza_flux), with the
// Jacobian -q'(T) phi_T,j phi_T,i; Navier walls + int_Gamma beta u . phi_u (the normal part is
// constrained to zero), beta = eta(T) / b or, with kinetic slip, the particle wall's own
// beta(n, T). `density_field`: the scalar component is n (compressible), else n is n0.
template <int dim> class WallTerms {
public:
  WallTerms(const dealii::FiniteElement<dim>& fe, const ContinuumParameters& prm,
            bool density_field = false)
      : prm_(prm), density_field_(density_field), quadrature_(3),
        fe_face_values_(fe, quadrature_, dealii::update_values | dealii::update_JxW_values),
        n_(fe.n_dofs_per_cell()), T_(quadrature_.size()), density_(quadrature_.size()),
        u_(quadrature_.size()) {}

  template <class VectorType>
  void add(const CellIterator<dim>& cell, const VectorType& x, bool with_jacobian,
           CellSystem& out) {
    for (const auto& face : cell->face_iterators()) {
      if (!face->at_boundary()) continue;
      const int d = face->boundary_id() / 2, side = face->boundary_id() % 2;
      const auto& b = prm_.boundary[d];
      if (b.periodic) continue;
      const bool robin = b.robin(side);
      if (b.navier(side)) add_navier_traction(cell, face, x, b, side, with_jacobian, out);
      if (!robin && (b.fixed_temperature[side] || b.heat_flux[side] == 0.0)) continue;
      fe_face_values_.reinit(cell, face);
      if (robin) fe_face_values_[temperature_].get_function_values(x, T_);
      for (unsigned q = 0; q < quadrature_.size(); ++q) {
        const double JxW = fe_face_values_.JxW(q);
        const double flux_in = robin ? b.kapitza_flux(side, T_[q]) : b.heat_flux[side];
        const double dflux = robin ? b.kapitza_flux_derivative(side, T_[q]) : 0.0;
        for (unsigned i = 0; i < n_; ++i) {
          const double phi_i = fe_face_values_[temperature_].value(i, q);
          out.rhs(i) += flux_in * phi_i * JxW;
          if (robin && with_jacobian)
            for (unsigned j = 0; j < n_; ++j)
              out.matrix(i, j) -= dflux * fe_face_values_[temperature_].value(j, q) * phi_i * JxW;
        }
      }
    }
  }

private:
  // Navier wall: residual + int beta u . phi_u,i; Jacobian beta phi_u,j . phi_u,i + (beta_T
  // phi_T,j + beta_n phi_n,j) u . phi_u,i.
  template <class Face, class VectorType>
  void add_navier_traction(const CellIterator<dim>& cell, const Face& face, const VectorType& x,
                           const DirectionBoundary& b, int side, bool with_jacobian,
                           CellSystem& out) {
    fe_face_values_.reinit(cell, face);
    fe_face_values_[temperature_].get_function_values(x, T_);
    fe_face_values_[velocities_].get_function_values(x, u_);
    const bool kinetic = b.kinetic_slip[side], with_density = kinetic && density_field_;
    if (with_density) fe_face_values_[scalar_].get_function_values(x, density_);
    const double T_ref = prm_.reference_temperature;
    for (unsigned q = 0; q < quadrature_.size(); ++q) {
      const double JxW = fe_face_values_.JxW(q);
      WallFriction::AtState f;
      if (kinetic) // references.md, "Kinetic slip at a particle wall"
        f = prm_.wall_friction.at(with_density ? density_[q] : prm_.number_density, T_[q],
                                  b.temperature[side], prm_.particle_mass);
      else // Navier (1823): the wall's traction eta u_t / b, its friction per area eta / b
        f = {prm_.viscosity.at(T_[q], T_ref) / b.slip_length[side],
             prm_.viscosity.derivative(T_[q], T_ref) / b.slip_length[side], 0.0};
      for (unsigned i = 0; i < n_; ++i) {
        const dealii::Tensor<1, dim> phi_i = fe_face_values_[velocities_].value(i, q);
        const double u_phi_i = u_[q] * phi_i;
        out.rhs(i) -= f.value * u_phi_i * JxW;
        if (!with_jacobian) continue;
        for (unsigned j = 0; j < n_; ++j) {
          double dj = f.value * (fe_face_values_[velocities_].value(j, q) * phi_i) +
                      f.d_T * fe_face_values_[temperature_].value(j, q) * u_phi_i;
          if (with_density) dj += f.d_n * fe_face_values_[scalar_].value(j, q) * u_phi_i;
          out.matrix(i, j) += dj * JxW;
        }
      }
    }
  }

  const ContinuumParameters& prm_;
  const bool density_field_;
  const dealii::QGauss<dim - 1> quadrature_;
  dealii::FEFaceValues<dim> fe_face_values_;
  const unsigned n_;
  const dealii::FEValuesExtractors::Vector velocities_{0};
  const dealii::FEValuesExtractors::Scalar scalar_{dim}, temperature_{dim + 1};
  std::vector<double> T_, density_;
  std::vector<dealii::Tensor<1, dim>> u_;
};

} // namespace twinflow::continuum
