#pragma once
// Post-processing of a Boussinesq state (u_0..u_{dim-1}, p, T), one place for the serial and the
// distributed solver: volume Nu with kinetic energy, max speed and mean T, wall Nu, the mid-line
// velocity maxima. VectorType: dealii::Vector or a ghosted Trilinos block vector; each process
// integrates over its own cells and the sums are taken over the triangulation's communicator
// (MPI_COMM_SELF for a serial mesh). Included only by the Boussinesq instantiation units.

#include <deal.II/base/mpi.h>
#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/numerics/vector_tools_evaluate.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"

namespace twinflow::continuum::detail {

struct FlowIntegrals {
  double nusselt = 0;          // volume form, 0 without a heated direction
  double kinetic_energy = 0;   // int (1/2) n m |u|^2 dV
  double max_speed = 0;        // max |u| at the quadrature points / (chi/H)
  double temperature_mean = 0; // (1/|Omega|) int T dV
};

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
template <int dim, class VectorType>
FlowIntegrals flow_integrals(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                             const ContinuumParameters& prm, const DimensionlessNumbers& numbers) {
  // Nu = (1/|Omega|) int (n c_p u_d (T - T_ref) - kappa dT/dx_d) / q_cond: the mean heat flux
  // across planes x_d = const over the conduction flux (build-notes; de Vahl Davis 1983 eq. 7
  // averaged over x).
  const int d = numbers.heated_direction;
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(dofs.get_fe(), quadrature,
                                  dealii::update_values | dealii::update_gradients |
                                      dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  std::vector<dealii::Tensor<1, dim>> u(quadrature.size()), grad_T(quadrature.size());
  std::vector<double> T(quadrature.size());
  const double ncp = prm.heat_capacity_per_volume(), T_ref = prm.reference_temperature;
  double flux = 0, volume = 0, kinetic = 0, max_speed = 0, temperature_integral = 0;
  for (const auto& cell : dofs.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    fe_values[velocities].get_function_values(x, u);
    fe_values[temperature].get_function_values(x, T);
    fe_values[temperature].get_function_gradients(x, grad_T);
    for (unsigned q = 0; q < quadrature.size(); ++q) {
      const double JxW = fe_values.JxW(q);
      if (d >= 0)
        flux += (ncp * u[q][d] * (T[q] - T_ref) - prm.conductivity.at(T[q], T_ref) * grad_T[q][d]) *
                JxW;
      kinetic += 0.5 * prm.mass_density() * u[q].norm_square() * JxW; // (1/2) n m |u|^2
      max_speed = std::max(max_speed, u[q].norm());
      temperature_integral += T[q] * JxW;
      volume += JxW;
    }
  }
  const MPI_Comm comm = communicator(dofs);
  volume = dealii::Utilities::MPI::sum(volume, comm);
  FlowIntegrals out;
  if (d >= 0)
    out.nusselt = dealii::Utilities::MPI::sum(flux, comm) / volume / numbers.conduction_flux;
  out.kinetic_energy = dealii::Utilities::MPI::sum(kinetic, comm);
  out.max_speed = dealii::Utilities::MPI::max(max_speed, comm) / numbers.velocity_scale;
  out.temperature_mean = dealii::Utilities::MPI::sum(temperature_integral, comm) / volume;
  return out;
}

// Local Nu = heat flux into the fluid (lower wall) or out of it (upper wall) over the conduction
// flux, +-kappa n.grad T / q_cond with n the outward normal, on both walls of the heated
// direction: the face average, and (on one process) the values at the face quadrature points.
template <int dim, class VectorType>
std::vector<WallNusselt> wall_nusselt(const dealii::DoFHandler<dim>& dofs, const VectorType& x,
                                      const ContinuumParameters& prm,
                                      const DimensionlessNumbers& numbers) {
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
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  std::vector<double> T(face_quadrature.size());
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
        fe_face_values[temperature].get_function_values(x, T);
        fe_face_values[temperature].get_function_gradients(x, grad_T);
        for (unsigned q = 0; q < face_quadrature.size(); ++q) {
          const double nu = (side == 0 ? 1.0 : -1.0) *
                            prm.conductivity.at(T[q], prm.reference_temperature) *
                            (grad_T[q] * fe_face_values.normal_vector(q)) / numbers.conduction_flux;
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

} // namespace twinflow::continuum::detail
