#pragma once
// FlowProblem<dim, Model, Backend>: included by the instantiation units only (one dimension per
// unit: compile memory, docs/build.md). Newton's method on the weak residual with its exact
// Jacobian and a backtracking line search (step-57); the residual is the model's.

#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include "continuum/fields.templates.hpp"
#include "continuum/flow_postprocess.templates.hpp"
#include "continuum/flow_problem.hpp"
#include "continuum/time_schedule.hpp"

namespace twinflow::continuum {

template <int dim> std::unique_ptr<dealii::Function<dim>> FlowModel<dim>::initial_state() const {
  if (!prm_.initial_temperature.empty()) {
    const std::shared_ptr<dealii::FunctionParser<dim>> expression =
        detail::initial_temperature_expression<dim>(prm_);
    return at_rest([expression](const dealii::Point<dim>& x) { return expression->value(x); });
  }
  return at_rest([this](const dealii::Point<dim>& x) { return conduction_profile(x); });
}

template <int dim> double FlowModel<dim>::conduction_profile(const dealii::Point<dim>& x) const {
  const int d = numbers_.heated_direction;
  if (d < 0) return prm_.reference_temperature;
  const auto& b = prm_.boundary[d];
  return b.temperature[0] + (b.temperature[1] - b.temperature[0]) * x[d] / numbers_.height;
}

template <int dim, class Model, class Backend>
FlowProblem<dim, Model, Backend>::FlowProblem(const ContinuumParameters& parameters, MPI_Comm comm)
    : prm_(parameters), numbers_(dimensionless_numbers(parameters)), backend_(prm_, comm),
      fe_(dealii::FE_Q<dim>(2), dim, dealii::FE_Q<dim>(Model::scalar_degree), 1,
          dealii::FE_Q<dim>(2), 1),
      dof_handler_(backend_.triangulation()), model_(prm_, numbers_, fe_),
      pcout_(std::cout, dealii::Utilities::MPI::this_mpi_process(backend_.communicator()) == 0) {
  static_assert(!(Model::global_scalar && Backend::distributed),
                "a rank-one term needs the serial backend (Sherman-Morrison)");
  check(prm_);
  if (prm_.dim != dim)
    throw std::invalid_argument(std::string(Model::name) + " flow: dimension mismatch");
}

template <int dim, class Model, class Backend>
ContinuumResult FlowProblem<dim, Model, Backend>::run(const std::filesystem::path& out) {
  ContinuumResult result;
  result.model = Model::name;
  result.dim = dim;
  result.numbers = numbers_;
  {
    detail::ScopedTimer timer(times_.setup);
    backend_.make_mesh();
  }
  if (prm_.transient())
    march_in_time(out, result);
  else
    solve_on_each_level(result);
  {
    detail::ScopedTimer timer(times_.postprocess);
    normalize_pressure();
    postprocess(result);
  }
  if (!out.empty() && !prm_.transient()) {
    detail::ScopedTimer timer(times_.output);
    output_fields(out, result);
  }
  result.times = times_;
  return result;
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::solve_on_each_level(ContinuumResult& result) {
  double previous_nusselt = 0;
  for (int level = 0; level <= prm_.refinements; ++level) {
    const auto start = std::chrono::steady_clock::now();
    const int iterations_before = newton_iterations_;
    if (level == 0) {
      setup_dofs();
      initial_guess();
      solve_with_continuation();
    } else {
      refine_mesh_and_transfer();
      int iterations = 0;
      if (!newton(1.0, iterations))
        throw std::runtime_error(std::string(Model::name) +
                                 ": Newton did not converge after refinement to level " +
                                 std::to_string(level));
    }
    result.mesh_study.push_back(finish_level(level, start, iterations_before, previous_nusselt));
    previous_nusselt = result.mesh_study.back().nusselt;
  }
}

template <int dim, class Model, class Backend>
MeshLevel
FlowProblem<dim, Model, Backend>::finish_level(int level,
                                               std::chrono::steady_clock::time_point start,
                                               int iterations_before, double previous_nusselt) {
  evaluation_point_ = solution_;
  model_.update_derived_state(dof_handler_, evaluation_point_);
  MeshLevel m;
  m.level = level;
  m.cells = backend_.cells();
  m.dofs = dof_handler_.n_dofs();
  {
    detail::ScopedTimer timer(times_.postprocess);
    m.nusselt = integrals().nusselt;
  }
  m.change_in_nusselt = level == 0 ? 0.0 : m.nusselt - previous_nusselt;
  m.pressure_ratio = model_.pressure_ratio();
  m.newton_iterations = newton_iterations_ - iterations_before;
  m.wall_time = detail::seconds_since(start);
  pcout_ << "continuum: level " << level << ", " << m.dofs << " DoFs" << backend_.where()
         << ", Nu = " << m.nusselt << model_.state_note() << ", " << m.newton_iterations
         << " Newton iterations, " << m.wall_time << " s" << std::endl;
  return m;
}

template <int dim, class Model, class Backend>
int FlowProblem<dim, Model, Backend>::step_in_time(int step, double time,
                                                   const std::array<double, 3>& bdf,
                                                   Vector& previous) {
  // d/dt x ~ a0 x + history, history from x^n and x^{n-1} (time_schedule.hpp).
  bdf_ = bdf;
  Vector history = solution_;
  history *= bdf_[1];
  history.add(bdf_[2], previous);
  history_ = history;
  older_ = previous;
  previous_ = solution_;
  previous = solution_;
  model_.begin_time_step(time);
  int iterations = 0;
  if (!newton(1.0, iterations))
    throw std::runtime_error(std::string(Model::name) + ": Newton did not converge in time step " +
                             std::to_string(step) + " (t = " + std::to_string(time) +
                             "); try a smaller time step");
  evaluation_point_ = solution_;
  model_.update_derived_state(dof_handler_, evaluation_point_);
  return iterations;
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::march_in_time(const std::filesystem::path& dir,
                                                     ContinuumResult& result) {
  // On the finest mesh from the initial state; one Newton solve per step, from the last state.
  {
    detail::ScopedTimer timer(times_.setup);
    backend_.refine(prm_.refinements);
  }
  setup_dofs();
  initial_guess();
  const detail::TimeSchedule schedule(prm_, Model::time_order);
  dt_ = schedule.dt();
  detail::FieldSeriesWriter<dim> snapshots(dir, backend_.communicator());
  auto record = [&](int step, int iterations) {
    normalize_pressure(); // the gauge of p does not enter the residual
    {
      detail::ScopedTimer timer(times_.postprocess);
      if (schedule.is_sample(step)) result.time_series.push_back(sample(step, iterations));
    }
    if (schedule.is_snapshot(step) && !dir.empty() && prm_.write_fields) {
      detail::ScopedTimer timer(times_.output);
      write_fields([&](const dealii::DataOut<dim>& data_out) {
        snapshots.write(data_out, schedule.time(step), result.files);
      });
    }
  };
  record(0, 0);

  Vector previous = solution_; // x^{n-1}
  for (auto* v : {&history_, &previous_, &older_}) backend_.reinit_ghosted(*v);
  const auto start = std::chrono::steady_clock::now();
  for (int step = 1; step <= schedule.steps(); ++step) {
    const int iterations =
        step_in_time(step, schedule.time(step), schedule.coefficients(step), previous);
    record(step, iterations);
    if (schedule.is_report(step)) {
      const TimeSample s = sample(step, iterations);
      pcout_ << "continuum: step " << step << "/" << schedule.steps() << ", t = " << s.time
             << ", Nu = " << s.nusselt << model_.state_note()
             << ", kinetic energy = " << s.kinetic_energy << ", max speed = " << s.max_speed
             << " chi/H, " << iterations << " Newton iterations, " << detail::seconds_since(start)
             << " s" << std::endl;
    }
  }
  bdf_ = {{0, 0, 0}};
  result.time = schedule.time(schedule.steps());
  result.time_steps = schedule.steps();
  result.time_step = schedule.dt();
}

template <int dim, class Model, class Backend> void FlowProblem<dim, Model, Backend>::setup_dofs() {
  detail::ScopedTimer timer(times_.setup);
  backend_.distribute_dofs(dof_handler_, fe_);
  make_constraints();
  model_.setup(dof_handler_, zero_constraints_);
  backend_.setup_matrix(dof_handler_, model_.coupling(), zero_constraints_);
  for (auto* v : {&solution_, &newton_update_, &residual_}) backend_.reinit(*v);
  backend_.reinit_ghosted(evaluation_point_);
  if constexpr (Model::global_scalar) {
    backend_.reinit(rank_one_column_);
    backend_.reinit(rank_one_row_);
  }
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::make_constraints() {
  // Walls: fixed temperatures (not Kapitza walls: their flux is in the residual), no slip (not
  // Navier walls: no normal flow, as free slip, with their traction in the residual).
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  const unsigned n_components = dim + 2;
  for (const bool homogeneous : {false, true}) {
    auto& c = homogeneous ? zero_constraints_ : nonzero_constraints_;
    backend_.clear_constraints(dof_handler_, c);
    dealii::DoFTools::make_hanging_node_constraints(dof_handler_, c);
    detail::add_periodicity(dof_handler_, prm_, c);
    std::set<dealii::types::boundary_id> free_slip_walls;
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
        if (b.no_slip && !b.navier(side))
          dealii::VectorTools::interpolate_boundary_values(
              dof_handler_, id, dealii::Functions::ZeroFunction<dim>(n_components), c,
              fe_.component_mask(velocities));
        else
          free_slip_walls.insert(id);
      }
    }
    if (!free_slip_walls.empty())
      dealii::VectorTools::compute_no_normal_flux_constraints(dof_handler_, 0, free_slip_walls, c);
    backend_.close_constraints(dof_handler_, Model::gauge_pressure, c);
  }
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::initial_guess() {
  dealii::VectorTools::interpolate(dof_handler_, *model_.initial_state(), solution_);
  nonzero_constraints_.distribute(solution_);
  model_.normalise_initial_state(dof_handler_, solution_);
  evaluation_point_ = solution_;
  model_.update_derived_state(dof_handler_, evaluation_point_);
}

template <int dim, class Model, class Backend>
double FlowProblem<dim, Model, Backend>::assemble(bool with_jacobian, double gravity_factor) {
  model_.begin_assembly(dof_handler_, evaluation_point_, with_jacobian);
  detail::ScopedTimer timer(times_.assembly);
  auto& jacobian = backend_.matrix();
  if (with_jacobian) {
    jacobian = 0;
    if constexpr (Model::global_scalar) {
      rank_one_column_ = 0;
      rank_one_row_ = 0;
    }
  }
  residual_ = 0;
  AssemblyContext<dim, GhostedVector> context;
  context.with_jacobian = with_jacobian;
  for (int d = 0; d < dim; ++d) context.gravity[d] = gravity_factor * prm_.gravity[d];
  if (bdf_[0] > 0) {
    context.a0 = bdf_[0];
    context.c = {{bdf_[1], bdf_[2]}};
    context.history = &history_;
    context.previous = &previous_;
    context.older = &older_;
  }
  CellSystem cell(fe_.n_dofs_per_cell());
  std::vector<dealii::types::global_dof_index> dofs(fe_.n_dofs_per_cell());
  for (const auto& c : dof_handler_.active_cell_iterators()) {
    if (!c->is_locally_owned()) continue;
    cell.matrix = 0;
    cell.rhs = 0;
    if constexpr (Model::global_scalar) {
      cell.column = 0;
      cell.row = 0;
    }
    model_.assemble_cell(c, evaluation_point_, context, cell);
    c->get_dof_indices(dofs);
    if (!with_jacobian) {
      zero_constraints_.distribute_local_to_global(cell.rhs, dofs, residual_);
      continue;
    }
    zero_constraints_.distribute_local_to_global(cell.matrix, cell.rhs, dofs, jacobian, residual_);
    if constexpr (Model::global_scalar) {
      zero_constraints_.distribute_local_to_global(cell.column, dofs, rank_one_column_);
      for (unsigned i = 0; i < dofs.size(); ++i) rank_one_row_(dofs[i]) += cell.row(i); // raw
    }
  }
  if (with_jacobian) jacobian.compress(dealii::VectorOperation::add);
  residual_.compress(dealii::VectorOperation::add);
  if constexpr (Model::global_scalar)
    if (with_jacobian) model_.end_assembly(rank_one_row_);
  return residual_.l2_norm();
}

template <int dim, class Model, class Backend>
bool FlowProblem<dim, Model, Backend>::newton(double gravity_factor, int& iterations) {
  // Convergence on the relative update of velocity and temperature separately (pressure is a
  // multiplier of the velocity); the scales keep a field at rest from dividing by zero.
  const double n_dofs_root = std::sqrt(static_cast<double>(dof_handler_.n_dofs()));
  const double velocity_floor = numbers_.velocity_scale * n_dofs_root;
  const double temperature_floor =
      std::max(std::abs(numbers_.temperature_difference), prm_.reference_temperature) * n_dofs_root;
  const Vector* column = Model::global_scalar ? &rank_one_column_ : nullptr;
  const Vector* row = Model::global_scalar ? &rank_one_row_ : nullptr;

  evaluation_point_ = solution_;
  double residual_norm = assemble(true, gravity_factor);
  Vector trial = solution_;
  for (int it = 0; it < prm_.max_newton_iterations; ++it) {
    unsigned linear = 0;
    {
      detail::ScopedTimer timer(times_.solve);
      linear =
          backend_.solve(dof_handler_, residual_, newton_update_, zero_constraints_, column, row);
    }
    // Backtracking line search on the residual norm (step-57); a state the model rejects (an
    // exception from its assembly: low-Mach T <= 0) counts as a larger residual.
    double step = 1.0, new_norm = 0;
    for (;;) {
      trial = solution_;
      trial.add(step, newton_update_);
      evaluation_point_ = trial;
      bool admissible = true;
      try {
        new_norm = assemble(false, gravity_factor);
      } catch (const std::runtime_error&) {
        admissible = false;
        new_norm = std::numeric_limits<double>::infinity();
      }
      if ((admissible && new_norm < residual_norm) || step < 1.0 / 32) break;
      step /= 2;
    }
    if (!std::isfinite(new_norm)) return false;
    solution_ = trial;
    ++iterations;
    ++newton_iterations_;
    const auto dx = backend_.velocity_temperature_norms(newton_update_);
    const auto x = backend_.velocity_temperature_norms(solution_);
    const double change = std::max(step * dx[0] / (x[0] + 1e-3 * velocity_floor),
                                   step * dx[1] / (x[1] + 1e-3 * temperature_floor));
    if (std::getenv("TWINFLOW_NEWTON_DEBUG"))
      pcout_ << "  newton " << it << ": residual " << residual_norm << " -> " << new_norm
             << ", step " << step << ", change " << change << model_.state_note() << ", " << linear
             << " linear iterations" << std::endl;
    if (change < prm_.newton_tolerance) return true;
    residual_norm = assemble(true, gravity_factor);
  }
  return false;
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::solve_with_continuation() {
  const double target = numbers_.rayleigh, start = prm_.continuation_start_rayleigh;
  std::vector<double> factors; // gravity multipliers: Ra of a step = factor * target
  // (1 - 1e-12): Ra computed from g may exceed a power of 10 by round-off (no repeated step).
  for (double ra = start; ra < target * (1 - 1e-12) && target > 0; ra *= 10)
    factors.push_back(ra / target);
  factors.push_back(1.0);
  double reached = 0.0;
  Vector last_converged = solution_;
  int failures = 0;
  for (std::size_t k = 0; k < factors.size();) {
    int iterations = 0;
    if (newton(factors[k], iterations)) {
      last_converged = solution_;
      reached = factors[k];
      continuation_rayleigh_.push_back(factors[k] * target);
      pcout_ << "continuum: Ra = " << factors[k] * target << " converged in " << iterations
             << " Newton iterations" << std::endl;
      ++k;
    } else {
      if (++failures > 10)
        throw std::runtime_error(
            std::string(Model::name) +
            ": Newton did not converge on the way to Ra = " + std::to_string(factors[k] * target));
      solution_ = last_converged;
      const double from = reached > 0 ? reached : factors[k] / 10;
      factors.insert(factors.begin() + k, std::sqrt(from * factors[k])); // geometric mid-step
    }
  }
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::refine_mesh_and_transfer() {
  detail::ScopedTimer timer(times_.setup);
  backend_.refine_and_transfer(dof_handler_, solution_, [this] { setup_dofs(); });
  nonzero_constraints_.distribute(solution_);
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::normalize_pressure() {
  // The solve pinned p at one node (or left its constant free); report the gauge with zero mean
  // instead (Q1 Lagrange: a constant shift of the nodal values shifts the field).
  evaluation_point_ = solution_;
  if constexpr (!Model::gauge_pressure) return;
  const double mean = dealii::VectorTools::compute_mean_value(dof_handler_, dealii::QGauss<dim>(3),
                                                              evaluation_point_, dim);
  backend_.subtract_from_component(dof_handler_, dim, mean, solution_);
  evaluation_point_ = solution_;
}

template <int dim, class Model, class Backend>
FlowIntegrals FlowProblem<dim, Model, Backend>::integrals() const {
  return detail::flow_integrals(dof_handler_, evaluation_point_, prm_, numbers_, model_);
}

template <int dim, class Model, class Backend>
TimeSample FlowProblem<dim, Model, Backend>::sample(int step, int newton_iterations) const {
  return detail::time_sample(integrals(), step, dt_, newton_iterations);
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::postprocess(ContinuumResult& result) {
  // Reads evaluation_point_ (normalize_pressure made it the solution).
  const GhostedVector& x = evaluation_point_;
  model_.update_derived_state(dof_handler_, x);
  result.dofs = dof_handler_.n_dofs();
  result.cells = backend_.cells();
  result.newton_iterations = newton_iterations_;
  result.continuation_rayleigh = continuation_rayleigh_;
  const FlowIntegrals flow = integrals();
  // Steady: Nu of the finest level (the same state).
  result.nusselt = result.mesh_study.empty() ? flow.nusselt : result.mesh_study.back().nusselt;
  result.kinetic_energy = flow.kinetic_energy;
  result.max_speed = flow.max_speed;
  result.temperature_mean = flow.temperature_mean;
  result.walls = detail::wall_nusselt(dof_handler_, x, numbers_, model_);
  detail::midline_maxima(dof_handler_, x, prm_, numbers_, result);
  std::vector<std::string> names;
  for (int d = 0; d < dim; ++d) names.push_back(std::string("u_") + "xyz"[d]);
  names.push_back(Model::scalar_name);
  names.push_back("T");
  std::vector<detail::DerivedField> derived;
  for (const auto& f : model_.derived_fields()) {
    names.push_back(f.name);
    derived.push_back(f.value);
  }
  result.bins =
      detail::bin_averages(dof_handler_, x, names, prm_, backend_.communicator(), derived);
  if constexpr (!Backend::distributed) {
    if constexpr (Model::divergence_free)
      detail::stream_function(dof_handler_, x, prm_, numbers_, result);
    detail::probe(dof_handler_, x, prm_, result);
  }
  const auto range = backend_.component_range(dof_handler_, dim + 1, solution_);
  result.temperature_min = range.first, result.temperature_max = range.second;
  model_.finish_result(dof_handler_, x, flow, result);
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::write_fields(
    const std::function<void(const dealii::DataOut<dim>&)>& write) const {
  std::vector<std::string> names(dim, "velocity");
  names.push_back(Model::scalar_name);
  names.push_back("T");
  std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation> kinds(
      dim, dealii::DataComponentInterpretation::component_is_part_of_vector);
  kinds.push_back(dealii::DataComponentInterpretation::component_is_scalar);
  kinds.push_back(dealii::DataComponentInterpretation::component_is_scalar);
  const detail::DerivedFieldsPostprocessor<dim> derived(model_.derived_fields());
  dealii::DataOut<dim> data_out;
  data_out.attach_dof_handler(dof_handler_);
  data_out.add_data_vector(evaluation_point_, names, dealii::DataOut<dim>::type_dof_data, kinds);
  if (!derived.get_names().empty()) data_out.add_data_vector(evaluation_point_, derived);
  data_out.build_patches(2); // Q2 fields on 2x2 sub-cells
  write(data_out);
}

template <int dim, class Model, class Backend>
void FlowProblem<dim, Model, Backend>::output_fields(const std::filesystem::path& dir,
                                                     ContinuumResult& result) const {
  if (!prm_.write_fields) return;
  write_fields([&](const dealii::DataOut<dim>& data_out) {
    detail::write_hdf5_xdmf(data_out, dir, 0.0, result.files, backend_.communicator());
  });
}

template <int dim, class Model, class Backend>
dealii::Vector<double>
FlowProblem<dim, Model, Backend>::value_at(const dealii::Point<dim>& point) const {
  dealii::Vector<double> value(dim + 2);
  if constexpr (Backend::distributed)
    throw std::logic_error("value_at: serial backend only");
  else
    dealii::VectorTools::point_value(dof_handler_, solution_, point, value);
  return value;
}

template <int dim, class Model, class Backend>
std::array<double, 3>
FlowProblem<dim, Model, Backend>::l2_errors(const dealii::Function<dim>& exact) const {
  return l2_norms(solution_, exact);
}

template <int dim, class Model, class Backend>
std::array<double, 3>
FlowProblem<dim, Model, Backend>::l2_difference(const FlowProblem& other) const {
  Vector difference = solution_;
  difference -= other.solution_;
  return l2_norms(difference, dealii::Functions::ZeroFunction<dim>(dim + 2));
}

template <int dim, class Model, class Backend>
std::array<double, 3>
FlowProblem<dim, Model, Backend>::l2_norms(const Vector& x,
                                           const dealii::Function<dim>& exact) const {
  std::array<double, 3> errors{{0, 0, 0}};
  if constexpr (Backend::distributed) {
    throw std::logic_error("l2_errors: serial backend only");
  } else {
    const dealii::QGauss<dim> quadrature(4);
    const std::array<std::pair<unsigned, unsigned>, 3> ranges{
        {{0, dim}, {dim, dim + 1}, {dim + 1, dim + 2}}}; // u, s, T
    for (int k = 0; k < 3; ++k) {
      const dealii::ComponentSelectFunction<dim> select(ranges[k], dim + 2);
      dealii::Vector<float> per_cell(dof_handler_.get_triangulation().n_active_cells());
      dealii::VectorTools::integrate_difference(dof_handler_, x, exact, per_cell, quadrature,
                                                dealii::VectorTools::L2_norm, &select);
      errors[k] = dealii::VectorTools::compute_global_error(dof_handler_.get_triangulation(),
                                                            per_cell, dealii::VectorTools::L2_norm);
    }
  }
  return errors;
}

} // namespace twinflow::continuum
