#pragma once
// Post-processing of a flow state (u_0..u_{dim-1}, s, T), one place for every model and backend:
// volume Nu with kinetic energy, max speed, mean T and particle count; wall Nu (gradient and
// consistent flux); the mid-line velocity maxima; the stream function; derived fields for the
// output. The model enters through its number density n(s, T) (heat capacity per volume c_p n,
// mass density m n), its conductivity kappa(s, T) and its Nu flux scale. VectorType: dealii::Vector
// or a ghosted Trilinos block vector; each process integrates over its own cells and the sums are
// taken over the triangulation's communicator (MPI_COMM_SELF for a serial mesh). Included only by
// the instantiation units (through flow_problem.templates.hpp).

#include <deal.II/base/mpi.h>
#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/fe_field_function.h>
#include <deal.II/numerics/vector_tools.h>
#include <deal.II/numerics/vector_tools_evaluate.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "continuum/flow_model.hpp"
#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum::detail {

// The time-series row of step `step` (time step dt) from its flow integrals.
inline TimeSample time_sample(const FlowIntegrals& integrals, int step, double dt,
                              int newton_iterations) {
  TimeSample s;
  s.step = step;
  s.time = step * dt;
  s.nusselt = integrals.nusselt;
  s.kinetic_energy = integrals.kinetic_energy;
  s.max_speed = integrals.max_speed;
  s.newton_iterations = newton_iterations;
  return s;
}

template <int dim> MPI_Comm communicator(const dealii::DoFHandler<dim>& dofs) {
  return dofs.get_triangulation().get_communicator();
}

// One pass over the cells for the quantities recorded at every step of a run in time.
template <int dim, class VectorType, class Model>
FlowIntegrals flow_integrals(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                             const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
                             const Model& model) {
  // Nu = (1/|Omega|) int (n c_p u_d (T - T_ref) - kappa dT/dx_d) / q_cond: the mean heat flux
  // across planes x_d = const over the conduction flux (docs/build.md; de Vahl Davis 1983 eq. 7
  // averaged over x). In a steady state div(n c_p u (T - T_ref) - kappa grad T) = c_p (T - T_ref)
  // div(n u) = 0 (no sources), so this mean is the wall heat flux.
  const int d = numbers.heated_direction;
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(dofs.get_fe(), quadrature,
                                  dealii::update_values | dealii::update_gradients |
                                      dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar scalar(dim), temperature(dim + 1);
  std::vector<dealii::Tensor<1, dim>> u(quadrature.size()), grad_T(quadrature.size());
  std::vector<double> s(quadrature.size()), T(quadrature.size());
  const double cp = prm.heat_capacity, m = prm.particle_mass, T_ref = prm.reference_temperature;
  double flux = 0, volume = 0, kinetic = 0, max_speed = 0, temperature_integral = 0;
  double particles = 0;
  for (const auto& cell : dofs.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    fe_values[velocities].get_function_values(x, u);
    fe_values[scalar].get_function_values(x, s);
    fe_values[temperature].get_function_values(x, T);
    fe_values[temperature].get_function_gradients(x, grad_T);
    for (unsigned q = 0; q < quadrature.size(); ++q) {
      const double n = model.density(s[q], T[q]), JxW = fe_values.JxW(q);
      if (d >= 0)
        flux +=
            (cp * n * u[q][d] * (T[q] - T_ref) - model.conductivity(s[q], T[q]) * grad_T[q][d]) *
            JxW;
      kinetic += 0.5 * (n * m) * u[q].norm_square() * JxW; // (1/2) n m |u|^2
      max_speed = std::max(max_speed, u[q].norm());
      temperature_integral += T[q] * JxW;
      particles += n * JxW;
      volume += JxW;
    }
  }
  const MPI_Comm comm = communicator(dofs);
  volume = dealii::Utilities::MPI::sum(volume, comm);
  FlowIntegrals out;
  if (d >= 0)
    out.nusselt = dealii::Utilities::MPI::sum(flux, comm) / volume / model.nusselt_flux_scale();
  out.kinetic_energy = dealii::Utilities::MPI::sum(kinetic, comm);
  out.max_speed = dealii::Utilities::MPI::max(max_speed, comm) / numbers.velocity_scale;
  out.temperature_mean = dealii::Utilities::MPI::sum(temperature_integral, comm) / volume;
  out.particles = dealii::Utilities::MPI::sum(particles, comm);
  return out;
}

// Local Nu = heat flux into the fluid (lower wall) or out of it (upper wall) over the flux scale
// (the conduction flux, or the model's), +-kappa n.grad T / q_cond with n the outward normal, on
// both walls of the heated direction: the face average, and (on one process) the values at the
// face quadrature points.
template <int dim, class VectorType, class Model>
std::vector<WallNusselt> wall_nusselt(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                                      const DimensionlessNumbers& numbers, const Model& model) {
  const double flux_scale = model.nusselt_flux_scale();
  std::vector<WallNusselt> walls;
  const int d = numbers.heated_direction;
  if (d < 0) return walls;
  const MPI_Comm comm = communicator(dofs);
  const bool keep_points = dealii::Utilities::MPI::n_mpi_processes(comm) == 1;
  const dealii::QGauss<dim - 1> face_quadrature(3);
  dealii::FEFaceValues<dim> fe_face_values(
      dofs.get_fe(), face_quadrature,
      dealii::update_values | dealii::update_gradients | dealii::update_normal_vectors |
          dealii::update_quadrature_points | dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Scalar scalar(dim), temperature(dim + 1);
  std::vector<double> s(face_quadrature.size()), T(face_quadrature.size());
  std::vector<dealii::Tensor<1, dim>> grad_T(face_quadrature.size());
  for (int side = 0; side < 2; ++side) {
    WallNusselt wall;
    wall.direction = d;
    wall.side = side;
    double area = 0, integral = 0;
    for (const auto& cell : dofs.active_cell_iterators()) {
      if (!cell->is_locally_owned()) continue;
      for (const auto& face : cell->face_iterators()) {
        if (!face->at_boundary() || face->boundary_id() != static_cast<unsigned>(2 * d + side))
          continue;
        fe_face_values.reinit(cell, face);
        fe_face_values[scalar].get_function_values(x, s);
        fe_face_values[temperature].get_function_values(x, T);
        fe_face_values[temperature].get_function_gradients(x, grad_T);
        for (unsigned q = 0; q < face_quadrature.size(); ++q) {
          const double nu = (side == 0 ? 1.0 : -1.0) * model.conductivity(s[q], T[q]) *
                            (grad_T[q] * fe_face_values.normal_vector(q)) / flux_scale;
          if (keep_points) {
            std::array<double, 3> point{{0, 0, 0}};
            for (int k = 0; k < dim; ++k) point[k] = fe_face_values.quadrature_point(q)[k];
            wall.points.push_back(point);
            wall.local.push_back(nu);
          }
          integral += nu * fe_face_values.JxW(q);
          area += fe_face_values.JxW(q);
        }
      }
    }
    wall.average =
        dealii::Utilities::MPI::sum(integral, comm) / dealii::Utilities::MPI::sum(area, comm);
    walls.push_back(wall);
  }
  return walls;
}

// Maximum of f on [a, b]: `samples` equidistant values, then zooms into the bracket of the
// best value (two spacings wide), 21 values each and a 10x finer spacing, until the bracket is
// below 1e-9 (b - a). f maps a list of positions to their values; one (collective) call per
// round keeps the distributed evaluation cheap (8 rounds for 401 samples). Near a smooth
// interior maximum the sampled value is within O(spacing^2) of the true one.
template <class F> LineMaximum line_maximum(const F& f, double a, double b, int samples) {
  LineMaximum m;
  m.value = -1e300;
  double lo = a, hi = b;
  for (int n = samples;; n = 21) {
    const double h = (hi - lo) / (n - 1);
    std::vector<double> positions(n);
    for (int i = 0; i < n; ++i) positions[i] = lo + i * h;
    const std::vector<double> values = f(positions);
    for (int i = 0; i < n; ++i)
      if (values[i] > m.value) m.value = values[i], m.position = positions[i];
    if (2 * h < 1e-9 * (b - a)) break;
    lo = std::max(a, m.position - h), hi = std::min(b, m.position + h);
  }
  return m;
}

// de Vahl Davis 1983: max u on the vertical mid-line x = Lx/2 and max v on the horizontal
// mid-line y = Ly/2 (3D: in the plane z = Lz/2), velocities in units of chi/H, positions as
// fractions of the box. Point values through RemotePointEvaluation: collective, every process
// gets every value whichever process owns the cell.
template <int dim, class VectorType>
void midline_maxima(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                    const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
                    ContinuumResult& result) {
  const dealii::MappingQ1<dim> mapping;
  dealii::Utilities::MPI::RemotePointEvaluation<dim> evaluation;
  const double Lx = prm.box[0], Ly = prm.box[1];
  // Component `c` of the velocity / (chi/H) along the line through `fixed` in direction `along`.
  auto velocity_on_line = [&](int c, int along, double fixed) {
    return [&, c, along, fixed](const std::vector<double>& positions) {
      std::vector<dealii::Point<dim>> points(positions.size());
      for (std::size_t i = 0; i < positions.size(); ++i) {
        points[i][along] = positions[i];
        points[i][1 - along] = fixed;
        if (dim == 3) points[i][dim - 1] = 0.5 * prm.box[2];
      }
      evaluation.reinit(points, dofs.get_triangulation(), mapping);
      const auto values = dealii::VectorTools::point_values<dim + 2>(evaluation, dofs, x);
      std::vector<double> out(values.size());
      for (std::size_t i = 0; i < values.size(); ++i)
        out[i] = values[i][c] / numbers.velocity_scale;
      return out;
    };
  };
  result.has_midline_maxima = true;
  result.u_max_vertical_midline =
      line_maximum(velocity_on_line(0, 1, 0.5 * Lx), 0.0, Ly, prm.profile_samples);
  result.u_max_vertical_midline.position /= Ly;
  result.v_max_horizontal_midline =
      line_maximum(velocity_on_line(1, 0, 0.5 * Ly), 0.0, Lx, prm.profile_samples);
  result.v_max_horizontal_midline.position /= Lx;
}

// Heat into the fluid through each wall of the heated direction, int_wall kappa dT/dn (n
// outward), from the weak energy equation tested with w = 1 on that wall's T nodes, 0 elsewhere:
// Q = int (n c_p u.grad T w + kappa grad T.grad w - source w) (the consistent flux: Gresho, Lee,
// Sani et al., Int. J. Numer. Meth. Fluids 7 (1987) 371; converges faster than the wall
// gradient), over the wall area and the model's flux scale. Steady states; serial vectors.
template <int dim, class Model>
std::vector<double>
consistent_wall_nusselt(const dealii::DoFHandler<dim>& dofs, const dealii::Vector<double>& x,
                        const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
                        const Model& model) {
  std::vector<double> nusselt;
  const int d = numbers.heated_direction;
  if (d < 0) return nusselt;
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar scalar(dim), temperature(dim + 1);
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(dofs.get_fe(), quadrature,
                                  dealii::update_values | dealii::update_gradients |
                                      dealii::update_quadrature_points | dealii::update_JxW_values);
  std::vector<dealii::Tensor<1, dim>> u(quadrature.size()), grad_T(quadrature.size()),
      grad_w(quadrature.size());
  std::vector<double> s(quadrature.size()), T(quadrature.size()), w(quadrature.size());
  double area = 1;
  for (int k = 0; k < dim; ++k)
    if (k != d) area *= prm.box[k];
  for (int side = 0; side < 2; ++side) {
    dealii::Vector<double> indicator(dofs.n_dofs());
    for (const auto i :
         dealii::DoFTools::extract_boundary_dofs(dofs, dofs.get_fe().component_mask(temperature),
                                                 {dealii::types::boundary_id(2 * d + side)}))
      indicator[i] = 1.0;
    double Q = 0;
    for (const auto& cell : dofs.active_cell_iterators()) {
      fe_values.reinit(cell);
      fe_values[temperature].get_function_values(indicator, w);
      bool touches = false;
      for (const double v : w) touches = touches || v != 0.0;
      if (!touches) continue;
      fe_values[temperature].get_function_gradients(indicator, grad_w);
      fe_values[velocities].get_function_values(x, u);
      fe_values[scalar].get_function_values(x, s);
      fe_values[temperature].get_function_values(x, T);
      fe_values[temperature].get_function_gradients(x, grad_T);
      for (unsigned q = 0; q < quadrature.size(); ++q) {
        std::array<double, 3> x3{{0, 0, 0}};
        for (int k = 0; k < dim; ++k) x3[k] = fe_values.quadrature_point(q)[k];
        const double n = model.density(s[q], T[q]);
        Q += (prm.heat_capacity * n * (u[q] * grad_T[q]) * w[q] +
              model.conductivity(s[q], T[q]) * (grad_T[q] * grad_w[q]) -
              heat_source_density(prm, x3) * w[q]) *
             fe_values.JxW(q);
      }
    }
    nusselt.push_back((side == 0 ? 1.0 : -1.0) * Q / (area * model.nusselt_flux_scale()));
  }
  return nusselt;
}

// 2D walled cavities: -Laplace psi = omega = dv/dx - du/dy, psi = 0 on the walls
// (u = dpsi/dy, v = -dpsi/dx, for div u = 0), on Q2 over the flow's mesh. Serial vectors.
inline void solve_stream_function(const dealii::DoFHandler<2>& flow_dofs,
                                  const dealii::Vector<double>& x,
                                  const dealii::DoFHandler<2>& psi_dofs,
                                  dealii::Vector<double>& psi) {
  constexpr int dim = 2;
  const auto& triangulation = flow_dofs.get_triangulation();
  const auto& fe_psi = psi_dofs.get_fe();
  dealii::AffineConstraints<double> constraints;
  for (dealii::types::boundary_id id = 0; id < 4; ++id)
    dealii::VectorTools::interpolate_boundary_values(
        psi_dofs, id, dealii::Functions::ZeroFunction<dim>(), constraints);
  constraints.close();
  dealii::DynamicSparsityPattern dsp(psi_dofs.n_dofs());
  dealii::DoFTools::make_sparsity_pattern(psi_dofs, dsp, constraints, false);
  dealii::SparsityPattern sparsity;
  sparsity.copy_from(dsp);
  dealii::SparseMatrix<double> matrix(sparsity);
  dealii::Vector<double> rhs(psi_dofs.n_dofs());
  psi.reinit(psi_dofs.n_dofs());
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> psi_values(fe_psi, quadrature,
                                   dealii::update_values | dealii::update_gradients |
                                       dealii::update_JxW_values);
  dealii::FEValues<dim> flow_values(flow_dofs.get_fe(), quadrature, dealii::update_gradients);
  const dealii::FEValuesExtractors::Vector velocities(0);
  std::vector<dealii::Tensor<2, dim>> grad_u(quadrature.size());
  const unsigned n = fe_psi.n_dofs_per_cell();
  dealii::FullMatrix<double> cell_matrix(n, n);
  dealii::Vector<double> cell_rhs(n);
  std::vector<dealii::types::global_dof_index> dofs(n);
  for (const auto& cell : psi_dofs.active_cell_iterators()) {
    const typename dealii::DoFHandler<dim>::active_cell_iterator flow_cell(
        &triangulation, cell->level(), cell->index(), &flow_dofs);
    psi_values.reinit(cell);
    flow_values.reinit(flow_cell);
    flow_values[velocities].get_function_gradients(x, grad_u);
    cell_matrix = 0;
    cell_rhs = 0;
    for (unsigned q = 0; q < quadrature.size(); ++q) {
      const double vorticity = grad_u[q][1][0] - grad_u[q][0][1];
      for (unsigned i = 0; i < n; ++i) {
        for (unsigned j = 0; j < n; ++j)
          cell_matrix(i, j) +=
              psi_values.shape_grad(i, q) * psi_values.shape_grad(j, q) * psi_values.JxW(q);
        cell_rhs(i) += vorticity * psi_values.shape_value(i, q) * psi_values.JxW(q);
      }
    }
    cell->get_dof_indices(dofs);
    constraints.distribute_local_to_global(cell_matrix, cell_rhs, dofs, matrix, rhs);
  }
  dealii::SparseDirectUMFPACK solver;
  solver.initialize(matrix);
  solver.vmult(psi, rhs);
  constraints.distribute(psi);
}

// Where |psi| is largest in the box: a grid search, then two zooms by 10 around the best point.
// Returns the maximum and its position.
inline std::array<double, 3> largest_magnitude(const dealii::DoFHandler<2>& psi_dofs,
                                               const dealii::Vector<double>& psi, double Lx,
                                               double Ly) {
  dealii::Functions::FEFieldFunction<2> field(psi_dofs, psi);
  auto abs_psi = [&](double px, double py) {
    return std::abs(field.value(dealii::Point<2>(px, py)));
  };
  double best = -1, bx = 0.5 * Lx, by = 0.5 * Ly, hx = Lx / 100, hy = Ly / 100;
  double cx = 0.5 * Lx, cy = 0.5 * Ly;
  for (int zoom = 0; zoom < 3; ++zoom) {
    const int half = zoom == 0 ? 49 : 10;
    for (int i = -half; i <= half; ++i)
      for (int j = -half; j <= half; ++j) {
        const double px = std::clamp(cx + i * hx, 0.0, Lx), py = std::clamp(cy + j * hy, 0.0, Ly);
        if (const double v = abs_psi(px, py); v > best) best = v, bx = px, by = py;
      }
    cx = bx, cy = by, hx /= 10, hy /= 10;
  }
  return {{best, bx, by}};
}

// The 2D walled cavity's stream function maximum and vortex centre.
template <int dim>
void stream_function(const dealii::DoFHandler<dim>& flow_dofs, const dealii::Vector<double>& x,
                     const ContinuumParameters& prm, const DimensionlessNumbers& numbers,
                     ContinuumResult& result) {
  if constexpr (dim != 2) {
    (void)flow_dofs, (void)x, (void)prm, (void)numbers, (void)result;
    return;
  } else {
    if (prm.boundary[0].periodic || prm.boundary[1].periodic) return;
    const dealii::FE_Q<dim> fe_psi(2);
    dealii::DoFHandler<dim> psi_dofs(flow_dofs.get_triangulation());
    psi_dofs.distribute_dofs(fe_psi);
    dealii::Vector<double> psi;
    solve_stream_function(flow_dofs, x, psi_dofs, psi);
    const double Lx = prm.box[0], Ly = prm.box[1];
    const auto [best, bx, by] = largest_magnitude(psi_dofs, psi, Lx, Ly);
    // psi / chi (de Vahl Davis 1983 scaling), chi = velocity_scale * H.
    result.stream_function_max = best / (numbers.velocity_scale * numbers.height);
    result.vortex_centre = {{bx / Lx, by / Ly}};
  }
}

// The model's derived fields (NamedField) as DataOut output.
template <int dim> class DerivedFieldsPostprocessor : public dealii::DataPostprocessor<dim> {
public:
  explicit DerivedFieldsPostprocessor(std::vector<NamedField> fields)
      : fields_(std::move(fields)) {}
  std::vector<std::string> get_names() const override {
    std::vector<std::string> names;
    for (const auto& f : fields_) names.push_back(f.name);
    return names;
  }
  dealii::UpdateFlags get_needed_update_flags() const override { return dealii::update_values; }
  void evaluate_vector_field(const dealii::DataPostprocessorInputs::Vector<dim>& input,
                             std::vector<dealii::Vector<double>>& out) const override {
    for (unsigned q = 0; q < input.solution_values.size(); ++q)
      for (unsigned k = 0; k < fields_.size(); ++k)
        out[q](k) = fields_[k].value(input.solution_values[q]);
  }

private:
  std::vector<NamedField> fields_;
};

} // namespace twinflow::continuum::detail
