#pragma once
// BoussinesqProblem<dim>: included by boussinesq_2d.cpp and boussinesq_3d.cpp only.
//
// Equations and cell integrals: boussinesq_kernel.hpp. Newton's method on the weak residual with
// its exact Jacobian, direct solves; in time, one such solve per BDF2 step. Post-processing
// shared with the distributed solver: boussinesq_postprocess.templates.hpp.

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/fe_field_function.h>
#include <deal.II/numerics/solution_transfer.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <set>
#include <stdexcept>

#include "continuum/boussinesq.hpp"
#include "continuum/boussinesq_kernel.hpp"
#include "continuum/boussinesq_postprocess.templates.hpp"
#include "continuum/fields.templates.hpp"
#include "continuum/time_schedule.hpp"

namespace twinflow::continuum {

using detail::ScopedTimer;

template <int dim>
BoussinesqProblem<dim>::BoussinesqProblem(const ContinuumParameters& parameters)
    : prm_(parameters), numbers_(dimensionless_numbers(parameters)),
      fe_(dealii::FE_Q<dim>(2), dim, dealii::FE_Q<dim>(1), 1, dealii::FE_Q<dim>(2), 1),
      dof_handler_(triangulation_) {
  check(prm_);
  if (prm_.dim != dim) throw std::invalid_argument("BoussinesqProblem: dimension mismatch");
}

template <int dim> ContinuumResult BoussinesqProblem<dim>::run(const std::filesystem::path& out) {
  ContinuumResult result;
  result.model = "boussinesq";
  result.dim = dim;
  result.numbers = numbers_;
  {
    ScopedTimer timer(times_.setup);
    make_coarse_mesh();
  }
  if (prm_.transient())
    march_in_time(out, result);
  else
    solve_on_each_level(result);
  {
    ScopedTimer timer(times_.postprocess);
    normalize_pressure();
    postprocess(result);
  }
  if (!out.empty() && !prm_.transient()) {
    ScopedTimer timer(times_.output);
    output_fields(out, result);
  }
  result.times = times_;
  return result;
}

template <int dim> void BoussinesqProblem<dim>::solve_on_each_level(ContinuumResult& result) {
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
        throw std::runtime_error("Newton did not converge after refinement to level " +
                                 std::to_string(level_));
    }
    MeshLevel m;
    m.level = level_;
    m.cells = detail::current_cells(triangulation_, prm_);
    m.dofs = dof_handler_.n_dofs();
    {
      ScopedTimer timer(times_.postprocess);
      m.nusselt = detail::flow_integrals(dof_handler_, solution_, prm_, numbers_).nusselt;
    }
    m.change_in_nusselt = level_ == 0 ? 0.0 : m.nusselt - previous_nusselt;
    previous_nusselt = m.nusselt;
    m.newton_iterations = newton_iterations_ - iterations_before;
    m.wall_time = detail::seconds_since(start);
    result.mesh_study.push_back(m);
    std::cout << "continuum: level " << level_ << ", " << m.dofs << " DoFs, Nu = " << m.nusselt
              << ", " << m.newton_iterations << " Newton iterations, " << m.wall_time << " s"
              << std::endl;
  }
}

template <int dim>
void BoussinesqProblem<dim>::march_in_time(const std::filesystem::path& dir,
                                           ContinuumResult& result) {
  // On the finest mesh from the initial state; one Newton solve per step, from the last state.
  {
    ScopedTimer timer(times_.setup);
    detail::refine_uniformly(triangulation_, prm_, prm_.refinements);
  }
  level_ = prm_.refinements;
  setup_dofs();
  initial_guess();
  const detail::TimeSchedule schedule(prm_);
  dt_ = schedule.dt();
  detail::FieldSeriesWriter<dim> snapshots(dir);
  auto record = [&](int step, int iterations) {
    {
      ScopedTimer timer(times_.postprocess);
      if (schedule.is_sample(step)) result.time_series.push_back(sample(step, iterations));
    }
    if (schedule.is_snapshot(step) && !dir.empty() && prm_.write_fields) {
      ScopedTimer timer(times_.output);
      dealii::DataOut<dim> data_out;
      attach_fields(data_out);
      snapshots.write(data_out, schedule.time(step), result.files);
    }
  };
  record(0, 0);

  dealii::Vector<double> previous = solution_; // x^{n-1}
  history_.reinit(dof_handler_.n_dofs());
  const auto start = std::chrono::steady_clock::now();
  for (int step = 1; step <= schedule.steps(); ++step) {
    // d/dt x ~ a0 x + history, history from x^n and x^{n-1} (time_schedule.hpp).
    const auto c = schedule.coefficients(step);
    time_a0_ = c[0];
    history_.equ(c[1], solution_);
    history_.add(c[2], previous);
    previous = solution_;
    int iterations = 0;
    if (!newton(1.0, iterations))
      throw std::runtime_error("Newton did not converge in time step " + std::to_string(step) +
                               " (t = " + std::to_string(schedule.time(step)) +
                               "); try a smaller time step");
    normalize_pressure(); // the gauge of p does not enter the residual
    record(step, iterations);
    if (schedule.is_report(step)) {
      const TimeSample s = sample(step, iterations);
      std::cout << "continuum: step " << step << "/" << schedule.steps() << ", t = " << s.time
                << ", Nu = " << s.nusselt << ", kinetic energy = " << s.kinetic_energy
                << ", max speed = " << s.max_speed << " chi/H, " << iterations
                << " Newton iterations, " << detail::seconds_since(start) << " s" << std::endl;
    }
  }
  time_a0_ = 0;
  result.time = schedule.time(schedule.steps());
  result.time_steps = schedule.steps();
  result.time_step = schedule.dt();
}

template <int dim> void BoussinesqProblem<dim>::make_coarse_mesh() {
  detail::make_box_mesh(triangulation_, prm_);
}

template <int dim> void BoussinesqProblem<dim>::setup_dofs() {
  ScopedTimer timer(times_.setup);
  dof_handler_.distribute_dofs(fe_);
  make_constraints();
  // Couplings of the Jacobian: no pressure-pressure or pressure-temperature blocks.
  const unsigned p = dim, t = dim + 1;
  dealii::Table<2, dealii::DoFTools::Coupling> coupling(dim + 2, dim + 2);
  for (unsigned c = 0; c < dim + 2; ++c)
    for (unsigned d = 0; d < dim + 2; ++d)
      coupling[c][d] = ((c == p && (d == p || d == t)) || (c == t && d == p))
                           ? dealii::DoFTools::none
                           : dealii::DoFTools::always;
  dealii::DynamicSparsityPattern dsp(dof_handler_.n_dofs());
  dealii::DoFTools::make_sparsity_pattern(dof_handler_, coupling, dsp, zero_constraints_, false);
  sparsity_pattern_.copy_from(dsp);
  jacobian_.reinit(sparsity_pattern_);
  for (auto* v : {&solution_, &evaluation_point_, &newton_update_, &residual_})
    v->reinit(dof_handler_.n_dofs());
}

template <int dim> void BoussinesqProblem<dim>::make_constraints() {
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
        if (b.fixed_temperature[side] && !b.robin(side)) {
          const double value = homogeneous ? 0.0 : b.temperature[side];
          dealii::VectorTools::interpolate_boundary_values(
              dof_handler_, id, dealii::Functions::ConstantFunction<dim>(value, n_components), c,
              fe_.component_mask(temperature));
        }
        if (b.no_slip && !b.navier(side)) // a Navier wall: no normal flow, as free slip
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
    // Walls everywhere (or periodic): p is fixed only up to a constant; pin one value.
    for (const auto i : dealii::DoFTools::extract_dofs(dof_handler_, fe_.component_mask(pressure)))
      if (!c.is_constrained(i)) {
        c.add_line(i);
        break;
      }
    c.close();
  }
}

template <int dim> void BoussinesqProblem<dim>::initial_guess() {
  // At rest, with the case's initial temperature or the conduction profile between the walls
  // of the heated direction.
  const int d = numbers_.heated_direction;
  const auto& b = prm_.boundary[std::max(d, 0)];
  const double T_ref = prm_.reference_temperature, H = numbers_.height;
  std::unique_ptr<dealii::FunctionParser<dim>> expression;
  if (!prm_.initial_temperature.empty())
    expression = detail::initial_temperature_expression<dim>(prm_);
  const dealii::VectorFunctionFromScalarFunctionObject<dim> initial(
      [&](const dealii::Point<dim>& x) {
        if (expression) return expression->value(x);
        return d < 0 ? T_ref : b.temperature[0] + (b.temperature[1] - b.temperature[0]) * x[d] / H;
      },
      dim + 1, dim + 2);
  dealii::VectorTools::interpolate(dof_handler_, initial, solution_);
  nonzero_constraints_.distribute(solution_);
}

template <int dim>
double BoussinesqProblem<dim>::assemble(bool with_jacobian, double gravity_factor) {
  ScopedTimer timer(times_.assembly);
  if (with_jacobian) jacobian_ = 0;
  residual_ = 0;
  BoussinesqCellKernel<dim> kernel(fe_, prm_);
  const unsigned n = fe_.n_dofs_per_cell();
  dealii::FullMatrix<double> cell_matrix(n, n);
  dealii::Vector<double> cell_rhs(n);
  std::vector<dealii::types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    kernel.assemble(cell, evaluation_point_, with_jacobian, gravity_factor, cell_matrix, cell_rhs,
                    time_a0_, time_a0_ > 0 ? &history_ : nullptr);
    cell->get_dof_indices(dofs);
    if (with_jacobian)
      zero_constraints_.distribute_local_to_global(cell_matrix, cell_rhs, dofs, jacobian_,
                                                   residual_);
    else
      zero_constraints_.distribute_local_to_global(cell_rhs, dofs, residual_);
  }
  return residual_.l2_norm();
}

template <int dim> void BoussinesqProblem<dim>::solve_linear_system() {
  ScopedTimer timer(times_.solve);
  direct_solver_.initialize(jacobian_);
  direct_solver_.vmult(newton_update_, residual_);
  zero_constraints_.distribute(newton_update_);
}

template <int dim> bool BoussinesqProblem<dim>::newton(double gravity_factor, int& iterations) {
  // Convergence on the relative update of velocity and temperature separately (pressure is a
  // multiplier of the velocity); the scales keep a field at rest from dividing by zero.
  std::vector<bool> is_velocity(dof_handler_.n_dofs(), false);
  {
    const dealii::FEValuesExtractors::Vector velocities(0);
    for (const auto i :
         dealii::DoFTools::extract_dofs(dof_handler_, fe_.component_mask(velocities)))
      is_velocity[i] = true;
  }
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
    // Backtracking line search on the residual norm (step-57).
    double step = 1.0, new_norm = 0;
    for (;;) {
      evaluation_point_ = solution_;
      evaluation_point_.add(step, newton_update_);
      new_norm = assemble(false, gravity_factor);
      if (new_norm < residual_norm || step < 1.0 / 32) break;
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
                << ", step " << step << ", change " << change << std::endl;
    if (change < prm_.newton_tolerance) return true;
    residual_norm = assemble(true, gravity_factor);
  }
  return false;
}

template <int dim> void BoussinesqProblem<dim>::solve_with_continuation() {
  const double target = numbers_.rayleigh, start = prm_.continuation_start_rayleigh;
  std::vector<double> factors; // gravity multipliers: Ra of a step = factor * target
  for (double ra = start; ra < target && target > 0; ra *= 10) factors.push_back(ra / target);
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
        throw std::runtime_error("Newton did not converge on the way to Ra = " +
                                 std::to_string(factors[k] * target));
      solution_ = last_converged;
      const double from = reached > 0 ? reached : factors[k] / 10;
      factors.insert(factors.begin() + k, std::sqrt(from * factors[k])); // geometric mid-step
    }
  }
}

template <int dim> void BoussinesqProblem<dim>::normalize_pressure() {
  // The solve pinned p at one node; report the gauge with zero mean instead (Q1 Lagrange: a
  // constant shift of the nodal values shifts the field).
  const double mean =
      dealii::VectorTools::compute_mean_value(dof_handler_, dealii::QGauss<dim>(3), solution_, dim);
  for (const auto i : dealii::DoFTools::extract_dofs(
           dof_handler_, fe_.component_mask(dealii::FEValuesExtractors::Scalar(dim))))
    solution_[i] -= mean;
}

template <int dim> void BoussinesqProblem<dim>::refine_mesh_and_transfer() {
  ScopedTimer timer(times_.setup);
  dealii::SolutionTransfer<dim> transfer(dof_handler_);
  detail::flag_uniform_refinement(triangulation_, prm_);
  triangulation_.prepare_coarsening_and_refinement();
  const dealii::Vector<double> coarse_solution = solution_; // setup_dofs() resets solution_
  transfer.prepare_for_coarsening_and_refinement(coarse_solution);
  triangulation_.execute_coarsening_and_refinement();
  setup_dofs();
  dealii::Vector<double> transferred(dof_handler_.n_dofs());
  transfer.interpolate(coarse_solution, transferred);
  solution_ = transferred;
  nonzero_constraints_.distribute(solution_);
}

template <int dim> void BoussinesqProblem<dim>::stream_function(ContinuumResult& result) const {
  // 2D walled cavities: -Laplace psi = omega = dv/dx - du/dy, psi = 0 on the walls
  // (u = dpsi/dy, v = -dpsi/dx); the vortex centre is where |psi| is largest.
  if constexpr (dim != 2) {
    (void)result;
    return;
  } else {
    if (prm_.boundary[0].periodic || prm_.boundary[1].periodic) return;
    const dealii::FE_Q<dim> fe_psi(2);
    dealii::DoFHandler<dim> psi_dofs(triangulation_);
    psi_dofs.distribute_dofs(fe_psi);
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
    dealii::Vector<double> rhs(psi_dofs.n_dofs()), psi(psi_dofs.n_dofs());
    const dealii::QGauss<dim> quadrature(3);
    dealii::FEValues<dim> psi_values(fe_psi, quadrature,
                                     dealii::update_values | dealii::update_gradients |
                                         dealii::update_JxW_values);
    dealii::FEValues<dim> flow_values(fe_, quadrature, dealii::update_gradients);
    const dealii::FEValuesExtractors::Vector velocities(0);
    std::vector<dealii::Tensor<2, dim>> grad_u(quadrature.size());
    const unsigned n = fe_psi.n_dofs_per_cell();
    dealii::FullMatrix<double> cell_matrix(n, n);
    dealii::Vector<double> cell_rhs(n);
    std::vector<dealii::types::global_dof_index> dofs(n);
    for (const auto& cell : psi_dofs.active_cell_iterators()) {
      const typename dealii::DoFHandler<dim>::active_cell_iterator flow_cell(
          &triangulation_, cell->level(), cell->index(), &dof_handler_);
      psi_values.reinit(cell);
      flow_values.reinit(flow_cell);
      flow_values[velocities].get_function_gradients(solution_, grad_u);
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

    dealii::Functions::FEFieldFunction<dim> field(psi_dofs, psi);
    const double Lx = prm_.box[0], Ly = prm_.box[1];
    auto abs_psi = [&](double x, double y) {
      return std::abs(field.value(dealii::Point<dim>(x, y)));
    };
    // Grid search, then two zooms by 10 around the best point.
    double best = -1, bx = 0.5 * Lx, by = 0.5 * Ly, hx = Lx / 100, hy = Ly / 100;
    double cx = 0.5 * Lx, cy = 0.5 * Ly;
    for (int zoom = 0; zoom < 3; ++zoom) {
      const int half = zoom == 0 ? 49 : 10;
      for (int i = -half; i <= half; ++i)
        for (int j = -half; j <= half; ++j) {
          const double x = std::clamp(cx + i * hx, 0.0, Lx), y = std::clamp(cy + j * hy, 0.0, Ly);
          if (const double v = abs_psi(x, y); v > best) best = v, bx = x, by = y;
        }
      cx = bx, cy = by, hx /= 10, hy /= 10;
    }
    // psi / chi (de Vahl Davis 1983 scaling), chi = velocity_scale * H.
    result.stream_function_max = best / (numbers_.velocity_scale * numbers_.height);
    result.vortex_centre = {{bx / Lx, by / Ly}};
  }
}

template <int dim> void BoussinesqProblem<dim>::postprocess(ContinuumResult& result) const {
  result.dofs = dof_handler_.n_dofs();
  result.cells = detail::current_cells(triangulation_, prm_);
  result.newton_iterations = newton_iterations_;
  result.continuation_rayleigh = continuation_rayleigh_;
  const detail::FlowIntegrals integrals =
      detail::flow_integrals(dof_handler_, solution_, prm_, numbers_);
  result.nusselt = integrals.nusselt;
  result.kinetic_energy = integrals.kinetic_energy;
  result.max_speed = integrals.max_speed;
  result.temperature_mean = integrals.temperature_mean;
  result.walls = detail::wall_nusselt(dof_handler_, solution_, prm_, numbers_);
  detail::midline_maxima(dof_handler_, solution_, prm_, numbers_, result);
  stream_function(result);
  std::vector<std::string> names;
  for (int d = 0; d < dim; ++d) names.push_back(std::string("u_") + "xyz"[d]);
  names.push_back("p");
  names.push_back("T");
  result.bins = detail::bin_averages(dof_handler_, solution_, names, prm_);
  detail::probe(dof_handler_, solution_, prm_, result);
  // Temperature extremes at the nodes.
  result.temperature_min = 1e300, result.temperature_max = -1e300;
  const dealii::IndexSet temperature_dofs = dealii::DoFTools::extract_dofs(
      dof_handler_, fe_.component_mask(dealii::FEValuesExtractors::Scalar(dim + 1)));
  for (const auto i : temperature_dofs) {
    result.temperature_min = std::min(result.temperature_min, solution_[i]);
    result.temperature_max = std::max(result.temperature_max, solution_[i]);
  }
}

template <int dim>
TimeSample BoussinesqProblem<dim>::sample(int step, int newton_iterations) const {
  return detail::time_sample(detail::flow_integrals(dof_handler_, solution_, prm_, numbers_), step,
                             dt_, newton_iterations);
}

template <int dim>
void BoussinesqProblem<dim>::attach_fields(dealii::DataOut<dim>& data_out) const {
  std::vector<std::string> names(dim, "velocity");
  names.push_back("p");
  names.push_back("T");
  std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation> kinds(
      dim, dealii::DataComponentInterpretation::component_is_part_of_vector);
  kinds.push_back(dealii::DataComponentInterpretation::component_is_scalar);
  kinds.push_back(dealii::DataComponentInterpretation::component_is_scalar);
  data_out.attach_dof_handler(dof_handler_);
  data_out.add_data_vector(solution_, names, dealii::DataOut<dim>::type_dof_data, kinds);
  data_out.build_patches(2); // Q2 fields on 2x2 sub-cells
}

template <int dim>
void BoussinesqProblem<dim>::output_fields(const std::filesystem::path& dir,
                                           ContinuumResult& result) const {
  if (!prm_.write_fields) return;
  dealii::DataOut<dim> data_out;
  attach_fields(data_out);
  detail::write_hdf5_xdmf(data_out, dir, 0.0, result.files);
}

template <int dim>
dealii::Vector<double> BoussinesqProblem<dim>::value_at(const dealii::Point<dim>& point) const {
  dealii::Vector<double> value(dim + 2);
  dealii::VectorTools::point_value(dof_handler_, solution_, point, value);
  return value;
}

} // namespace twinflow::continuum
