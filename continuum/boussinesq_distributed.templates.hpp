#pragma once
// DistributedBoussinesqProblem<dim>: included by boussinesq_distributed_3d.cpp only.
// Equations and cell integrals: boussinesq_kernel.hpp; solver structure: step-32 / step-55
// (block-triangular preconditioner, AMG per block) and step-57 (Newton, line search).

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/block_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

#include "continuum/boussinesq_distributed.hpp"
#include "continuum/boussinesq_kernel.hpp"
#include "continuum/boussinesq_postprocess.templates.hpp"
#include "continuum/fields.templates.hpp"
#include "continuum/time_schedule.hpp"

namespace twinflow::continuum {

namespace detail {
using BlockVector = dealii::TrilinosWrappers::MPI::BlockVector;

// Upper block-triangular preconditioner of [A B^T C; B 0 0; D 0 E] (velocity, pressure,
// temperature; Elman, Silvester & Wathen 2014, ch. 9): z_p = -eta M_p^{-1} r_p (Schur complement
// -B A^{-1} B^T ~ -M_p / eta), z_u = A^{-1}(r_u - B^T z_p), z_T = E^{-1}(r_T - D z_u), with one
// AMG V-cycle for A^{-1} and E^{-1} and ILU for M_p^{-1}.
class BlockTriangularPreconditioner {
public:
  BlockTriangularPreconditioner(const dealii::TrilinosWrappers::BlockSparseMatrix& jacobian,
                                const dealii::TrilinosWrappers::PreconditionAMG& velocity,
                                const dealii::TrilinosWrappers::PreconditionILU& pressure_mass,
                                const dealii::TrilinosWrappers::PreconditionAMG& temperature,
                                double eta)
      : jacobian_(jacobian), velocity_(velocity), pressure_mass_(pressure_mass),
        temperature_(temperature), eta_(eta) {}

  void vmult(BlockVector& dst, const BlockVector& src) const {
    pressure_mass_.vmult(dst.block(1), src.block(1));
    dst.block(1) *= -eta_;
    tmp_u_.reinit(src.block(0), true);
    jacobian_.block(0, 1).vmult(tmp_u_, dst.block(1));
    tmp_u_.sadd(-1.0, src.block(0));
    velocity_.vmult(dst.block(0), tmp_u_);
    tmp_T_.reinit(src.block(2), true);
    jacobian_.block(2, 0).vmult(tmp_T_, dst.block(0));
    tmp_T_.sadd(-1.0, src.block(2));
    temperature_.vmult(dst.block(2), tmp_T_);
  }

private:
  const dealii::TrilinosWrappers::BlockSparseMatrix& jacobian_;
  const dealii::TrilinosWrappers::PreconditionAMG& velocity_;
  const dealii::TrilinosWrappers::PreconditionILU& pressure_mass_;
  const dealii::TrilinosWrappers::PreconditionAMG& temperature_;
  const double eta_;
  mutable dealii::TrilinosWrappers::MPI::Vector tmp_u_, tmp_T_;
};
} // namespace detail

template <int dim>
DistributedBoussinesqProblem<dim>::DistributedBoussinesqProblem(
    const ContinuumParameters& parameters, MPI_Comm comm)
    : comm_(comm), prm_(parameters), numbers_(dimensionless_numbers(parameters)),
      triangulation_(comm),
      fe_(dealii::FE_Q<dim>(2), dim, dealii::FE_Q<dim>(1), 1, dealii::FE_Q<dim>(2), 1),
      dof_handler_(triangulation_) {
  check(prm_);
  if (prm_.dim != dim)
    throw std::invalid_argument("DistributedBoussinesqProblem: dimension mismatch");
}

template <int dim>
ContinuumResult DistributedBoussinesqProblem<dim>::run(const std::filesystem::path& out) {
  ContinuumResult result;
  result.model = "boussinesq";
  result.dim = dim;
  result.numbers = numbers_;
  make_mesh();
  if (prm_.transient())
    march_in_time(out, result);
  else
    solve_on_each_level(result);
  {
    detail::ScopedTimer timer(times_.postprocess);
    normalize_pressure();
    postprocess(result);
  }
  if (!out.empty() && prm_.write_fields && !prm_.transient()) {
    detail::ScopedTimer timer(times_.output);
    output_fields(out, result);
  }
  result.times = times_;
  return result;
}

template <int dim> void DistributedBoussinesqProblem<dim>::normalize_pressure() {
  // Zero mean (the iterative solve leaves the constant undetermined); updates evaluation_point_.
  evaluation_point_ = solution_;
  const double mean = dealii::VectorTools::compute_mean_value(dof_handler_, dealii::QGauss<dim>(3),
                                                              evaluation_point_, dim);
  solution_.block(1).add(-mean);
  evaluation_point_ = solution_;
}

template <int dim> void DistributedBoussinesqProblem<dim>::make_mesh() {
  detail::ScopedTimer timer(times_.setup);
  detail::make_box_mesh(triangulation_, prm_);
  std::vector<dealii::GridTools::PeriodicFacePair<
      typename dealii::parallel::distributed::Triangulation<dim>::cell_iterator>>
      pairs;
  for (int d = 0; d < dim; ++d)
    if (prm_.boundary[d].periodic)
      dealii::GridTools::collect_periodic_faces(triangulation_, 2 * d, 2 * d + 1, d, pairs);
  if (!pairs.empty()) triangulation_.add_periodicity(pairs);
}

template <int dim>
void DistributedBoussinesqProblem<dim>::solve_on_each_level(ContinuumResult& result) {
  dealii::ConditionalOStream pcout(std::cout, dealii::Utilities::MPI::this_mpi_process(comm_) == 0);
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
        throw std::runtime_error("Newton did not converge after refinement to level " +
                                 std::to_string(level));
    }
    evaluation_point_ = solution_;
    MeshLevel m;
    m.level = level;
    for (int d = 0; d < dim; ++d) m.cells[d] = prm_.cells[d] << level;
    m.dofs = dof_handler_.n_dofs();
    {
      detail::ScopedTimer timer(times_.postprocess);
      m.nusselt = detail::flow_integrals(dof_handler_, evaluation_point_, prm_, numbers_).nusselt;
    }
    m.change_in_nusselt = level == 0 ? 0.0 : m.nusselt - previous_nusselt;
    previous_nusselt = m.nusselt;
    m.newton_iterations = newton_iterations_ - iterations_before;
    m.wall_time = detail::seconds_since(start);
    result.mesh_study.push_back(m);
    pcout << "continuum: level " << level << ", " << m.dofs << " DoFs on "
          << dealii::Utilities::MPI::n_mpi_processes(comm_) << " processes, Nu = " << m.nusselt
          << ", " << m.newton_iterations << " Newton iterations, " << m.wall_time << " s"
          << std::endl;
  }
}

template <int dim>
void DistributedBoussinesqProblem<dim>::march_in_time(const std::filesystem::path& dir,
                                                      ContinuumResult& result) {
  // As BoussinesqProblem::march_in_time: on the finest mesh, one Newton solve per step.
  dealii::ConditionalOStream pcout(std::cout, dealii::Utilities::MPI::this_mpi_process(comm_) == 0);
  {
    detail::ScopedTimer timer(times_.setup);
    triangulation_.refine_global(prm_.refinements);
  }
  setup_dofs();
  initial_guess();
  const detail::TimeSchedule schedule(prm_);
  dt_ = schedule.dt();
  detail::FieldSeriesWriter<dim> snapshots(dir, comm_);
  auto record = [&](int step, int iterations) {
    normalize_pressure(); // also the ghosted copy that the post-processing reads
    {
      detail::ScopedTimer timer(times_.postprocess);
      if (schedule.is_sample(step)) result.time_series.push_back(sample(step, iterations));
    }
    if (schedule.is_snapshot(step) && !dir.empty() && prm_.write_fields) {
      detail::ScopedTimer timer(times_.output);
      dealii::DataOut<dim> data_out;
      attach_fields(data_out);
      snapshots.write(data_out, schedule.time(step), result.files);
    }
  };
  record(0, 0);

  detail::BlockVector previous = solution_, history = solution_; // owned: x^{n-1}, history
  history_.reinit(owned_partitioning_, relevant_partitioning_, comm_);
  const auto start = std::chrono::steady_clock::now();
  for (int step = 1; step <= schedule.steps(); ++step) {
    // d/dt x ~ a0 x + history, history from x^n and x^{n-1} (time_schedule.hpp).
    const auto c = schedule.coefficients(step);
    time_a0_ = c[0];
    history = solution_;
    history *= c[1];
    history.add(c[2], previous);
    history_ = history;
    previous = solution_;
    int iterations = 0;
    if (!newton(1.0, iterations))
      throw std::runtime_error("Newton did not converge in time step " + std::to_string(step) +
                               " (t = " + std::to_string(schedule.time(step)) +
                               "); try a smaller time step");
    record(step, iterations);
    if (schedule.is_report(step)) {
      const TimeSample s = sample(step, iterations);
      pcout << "continuum: step " << step << "/" << schedule.steps() << ", t = " << s.time
            << ", Nu = " << s.nusselt << ", kinetic energy = " << s.kinetic_energy
            << ", max speed = " << s.max_speed << " chi/H, " << iterations << " Newton iterations, "
            << detail::seconds_since(start) << " s" << std::endl;
    }
  }
  time_a0_ = 0;
  result.time = schedule.time(schedule.steps());
  result.time_steps = schedule.steps();
  result.time_step = schedule.dt();
}

template <int dim>
TimeSample DistributedBoussinesqProblem<dim>::sample(int step, int newton_iterations) const {
  // Reads evaluation_point_ (the ghosted copy of the solution).
  return detail::time_sample(
      detail::flow_integrals(dof_handler_, evaluation_point_, prm_, numbers_), step, dt_,
      newton_iterations);
}

template <int dim> void DistributedBoussinesqProblem<dim>::setup_dofs() {
  detail::ScopedTimer timer(times_.setup);
  dof_handler_.distribute_dofs(fe_);
  // Blocks: velocity, pressure, temperature.
  std::vector<unsigned> block_component(dim + 2, 0);
  block_component[dim] = 1;
  block_component[dim + 1] = 2;
  dealii::DoFRenumbering::component_wise(dof_handler_, block_component);
  const auto per_block = dealii::DoFTools::count_dofs_per_fe_block(dof_handler_, block_component);
  const dealii::IndexSet owned = dof_handler_.locally_owned_dofs();
  const dealii::IndexSet relevant = dealii::DoFTools::extract_locally_relevant_dofs(dof_handler_);
  owned_partitioning_.clear();
  relevant_partitioning_.clear();
  dealii::types::global_dof_index begin = 0;
  for (unsigned b = 0; b < 3; ++b) {
    owned_partitioning_.push_back(owned.get_view(begin, begin + per_block[b]));
    relevant_partitioning_.push_back(relevant.get_view(begin, begin + per_block[b]));
    begin += per_block[b];
  }
  make_constraints();

  const unsigned p = dim, t = dim + 1;
  dealii::Table<2, dealii::DoFTools::Coupling> coupling(dim + 2, dim + 2);
  for (unsigned c = 0; c < dim + 2; ++c)
    for (unsigned d = 0; d < dim + 2; ++d)
      coupling[c][d] = ((c == p && d == t) || (c == t && d == p)) ? dealii::DoFTools::none
                                                                  : dealii::DoFTools::always;
  dealii::BlockDynamicSparsityPattern dsp(relevant_partitioning_);
  dealii::DoFTools::make_sparsity_pattern(dof_handler_, coupling, dsp, zero_constraints_, false,
                                          dealii::Utilities::MPI::this_mpi_process(comm_));
  dealii::SparsityTools::distribute_sparsity_pattern(dsp, owned, comm_, relevant);
  jacobian_.reinit(owned_partitioning_, dsp, comm_);
  preconditioner_matrix_.reinit(owned_partitioning_, dsp, comm_);
  solution_.reinit(owned_partitioning_, comm_);
  newton_update_.reinit(owned_partitioning_, comm_);
  residual_.reinit(owned_partitioning_, comm_);
  evaluation_point_.reinit(owned_partitioning_, relevant_partitioning_, comm_);
  assemble_pressure_mass();
}

template <int dim> void DistributedBoussinesqProblem<dim>::make_constraints() {
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  const unsigned n_components = dim + 2;
  const dealii::IndexSet relevant = dealii::DoFTools::extract_locally_relevant_dofs(dof_handler_);
  for (const bool homogeneous : {false, true}) {
    auto& c = homogeneous ? zero_constraints_ : nonzero_constraints_;
    c.clear();
    c.reinit(relevant);
    dealii::DoFTools::make_hanging_node_constraints(dof_handler_, c);
    detail::add_periodicity(dof_handler_, prm_, c);
    std::set<dealii::types::boundary_id> free_slip_walls;
    for (int d = 0; d < dim; ++d) {
      const auto& b = prm_.boundary[d];
      if (b.periodic) continue;
      for (int side = 0; side < 2; ++side) {
        const dealii::types::boundary_id id = 2 * d + side;
        if (b.fixed_temperature[side] && !b.robin(side))
          dealii::VectorTools::interpolate_boundary_values(
              dof_handler_, id,
              dealii::Functions::ConstantFunction<dim>(homogeneous ? 0.0 : b.temperature[side],
                                                       n_components),
              c, fe_.component_mask(temperature));
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
    // No pressure pin: the Krylov solver tolerates the constant null space (consistent
    // right-hand side: int div v = 0 for walls and periodic faces).
    c.close();
  }
}

template <int dim> void DistributedBoussinesqProblem<dim>::assemble_pressure_mass() {
  // (1/eta_ref) M_p, the Schur-complement approximation (Elman, Silvester & Wathen 2014, ch. 9).
  preconditioner_matrix_ = 0;
  const dealii::QGauss<dim> quadrature(3);
  dealii::FEValues<dim> fe_values(fe_, quadrature,
                                  dealii::update_values | dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Scalar pressure(dim);
  const unsigned n = fe_.n_dofs_per_cell();
  dealii::FullMatrix<double> cell_matrix(n, n);
  std::vector<dealii::types::global_dof_index> dofs(n);
  const double eta = prm_.viscosity.at(prm_.reference_temperature, prm_.reference_temperature);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    cell_matrix = 0;
    for (unsigned q = 0; q < quadrature.size(); ++q)
      for (unsigned i = 0; i < n; ++i)
        for (unsigned j = 0; j < n; ++j)
          cell_matrix(i, j) += fe_values[pressure].value(i, q) * fe_values[pressure].value(j, q) /
                               eta * fe_values.JxW(q);
    cell->get_dof_indices(dofs);
    zero_constraints_.distribute_local_to_global(cell_matrix, dofs, preconditioner_matrix_);
  }
  preconditioner_matrix_.compress(dealii::VectorOperation::add);
}

template <int dim> void DistributedBoussinesqProblem<dim>::initial_guess() {
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
}

template <int dim>
double DistributedBoussinesqProblem<dim>::assemble(bool with_jacobian, double gravity_factor) {
  detail::ScopedTimer timer(times_.assembly);
  if (with_jacobian) jacobian_ = 0;
  residual_ = 0;
  BoussinesqCellKernel<dim> kernel(fe_, prm_);
  const unsigned n = fe_.n_dofs_per_cell();
  dealii::FullMatrix<double> cell_matrix(n, n);
  dealii::Vector<double> cell_rhs(n);
  std::vector<dealii::types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    kernel.assemble(cell, evaluation_point_, with_jacobian, gravity_factor, cell_matrix, cell_rhs,
                    time_a0_, time_a0_ > 0 ? &history_ : nullptr);
    cell->get_dof_indices(dofs);
    if (with_jacobian)
      zero_constraints_.distribute_local_to_global(cell_matrix, cell_rhs, dofs, jacobian_,
                                                   residual_);
    else
      zero_constraints_.distribute_local_to_global(cell_rhs, dofs, residual_);
  }
  if (with_jacobian) jacobian_.compress(dealii::VectorOperation::add);
  residual_.compress(dealii::VectorOperation::add);
  return residual_.l2_norm();
}

template <int dim> unsigned DistributedBoussinesqProblem<dim>::solve_linear_system() {
  detail::ScopedTimer timer(times_.solve);
  const dealii::FEValuesExtractors::Vector velocities(0);
  const dealii::FEValuesExtractors::Scalar temperature(dim + 1);
  dealii::TrilinosWrappers::PreconditionAMG velocity_amg, temperature_amg;
  {
    dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
    dealii::DoFTools::extract_constant_modes(dof_handler_, fe_.component_mask(velocities),
                                             data.constant_modes);
    data.elliptic = true;
    data.higher_order_elements = true;
    data.smoother_sweeps = 2;
    data.aggregation_threshold = 0.02;
    velocity_amg.initialize(jacobian_.block(0, 0), data);
  }
  {
    dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
    dealii::DoFTools::extract_constant_modes(dof_handler_, fe_.component_mask(temperature),
                                             data.constant_modes);
    data.elliptic = true;
    data.higher_order_elements = true;
    data.smoother_sweeps = 2;
    data.aggregation_threshold = 0.02;
    temperature_amg.initialize(jacobian_.block(2, 2), data);
  }
  dealii::TrilinosWrappers::PreconditionILU pressure_ilu;
  pressure_ilu.initialize(preconditioner_matrix_.block(1, 1));
  const detail::BlockTriangularPreconditioner preconditioner(
      jacobian_, velocity_amg, pressure_ilu, temperature_amg,
      prm_.viscosity.at(prm_.reference_temperature, prm_.reference_temperature));
  // Inexact Newton: 1e-8 of the residual keeps the outer convergence (near) quadratic down to
  // the Newton tolerance; the floor (1e-14 of the first residual) stops the last iterations
  // from chasing round-off. Not reaching it is left to Newton's own convergence test.
  const double norm = residual_.l2_norm();
  if (first_residual_ == 0) first_residual_ = norm;
  dealii::SolverControl control(1000, std::max(1e-8 * norm, 1e-14 * first_residual_));
  dealii::SolverFGMRES<detail::BlockVector> solver(
      control, dealii::SolverFGMRES<detail::BlockVector>::AdditionalData(100));
  newton_update_ = 0;
  try {
    solver.solve(jacobian_, newton_update_, residual_, preconditioner);
  } catch (const dealii::SolverControl::NoConvergence&) {
  }
  zero_constraints_.distribute(newton_update_);
  linear_iterations_ += control.last_step();
  return control.last_step();
}

template <int dim>
bool DistributedBoussinesqProblem<dim>::newton(double gravity_factor, int& iterations) {
  // As BoussinesqProblem::newton: relative update of velocity and temperature below tolerance.
  const double n_root = std::sqrt(static_cast<double>(dof_handler_.n_dofs()));
  const double velocity_floor = 1e-3 * numbers_.velocity_scale * n_root;
  const double temperature_floor =
      1e-3 * std::max(std::abs(numbers_.temperature_difference), prm_.reference_temperature) *
      n_root;
  evaluation_point_ = solution_;
  double residual_norm = assemble(true, gravity_factor);
  detail::BlockVector trial(owned_partitioning_, comm_);
  for (int it = 0; it < prm_.max_newton_iterations; ++it) {
    const unsigned linear = solve_linear_system();
    double step = 1.0, new_norm = 0;
    for (;;) { // backtracking line search on the residual norm (step-57)
      trial = solution_;
      trial.add(step, newton_update_);
      evaluation_point_ = trial;
      new_norm = assemble(false, gravity_factor);
      if (new_norm < residual_norm || step < 1.0 / 32) break;
      step /= 2;
    }
    if (!std::isfinite(new_norm)) return false;
    solution_ = trial;
    ++iterations;
    ++newton_iterations_;
    const double change = std::max(step * newton_update_.block(0).l2_norm() /
                                       (solution_.block(0).l2_norm() + velocity_floor),
                                   step * newton_update_.block(2).l2_norm() /
                                       (solution_.block(2).l2_norm() + temperature_floor));
    if (std::getenv("TWINFLOW_NEWTON_DEBUG") &&
        dealii::Utilities::MPI::this_mpi_process(comm_) == 0)
      std::cout << "  newton " << it << ": residual " << residual_norm << " -> " << new_norm
                << ", step " << step << ", change " << change << ", " << linear
                << " FGMRES iterations" << std::endl;
    if (change < prm_.newton_tolerance) return true;
    residual_norm = assemble(true, gravity_factor);
  }
  return false;
}

template <int dim> void DistributedBoussinesqProblem<dim>::solve_with_continuation() {
  // As BoussinesqProblem::solve_with_continuation.
  const double target = numbers_.rayleigh, start = prm_.continuation_start_rayleigh;
  std::vector<double> factors;
  for (double ra = start; ra < target && target > 0; ra *= 10) factors.push_back(ra / target);
  factors.push_back(1.0);
  double reached = 0.0;
  detail::BlockVector last_converged = solution_;
  int failures = 0;
  for (std::size_t k = 0; k < factors.size();) {
    int iterations = 0;
    if (newton(factors[k], iterations)) {
      last_converged = solution_;
      reached = factors[k];
      continuation_rayleigh_.push_back(factors[k] * target);
      ++k;
    } else {
      if (++failures > 10)
        throw std::runtime_error("Newton did not converge on the way to Ra = " +
                                 std::to_string(factors[k] * target));
      solution_ = last_converged;
      const double from = reached > 0 ? reached : factors[k] / 10;
      factors.insert(factors.begin() + k, std::sqrt(from * factors[k]));
    }
  }
}

template <int dim> void DistributedBoussinesqProblem<dim>::refine_mesh_and_transfer() {
  detail::ScopedTimer timer(times_.setup);
  dealii::parallel::distributed::SolutionTransfer<dim, detail::BlockVector> transfer(dof_handler_);
  detail::BlockVector ghosted(owned_partitioning_, relevant_partitioning_, comm_);
  ghosted = solution_;
  triangulation_.set_all_refine_flags();
  triangulation_.prepare_coarsening_and_refinement();
  transfer.prepare_for_coarsening_and_refinement(ghosted);
  triangulation_.execute_coarsening_and_refinement();
  setup_dofs();
  transfer.interpolate(solution_);
  nonzero_constraints_.distribute(solution_);
}

template <int dim>
void DistributedBoussinesqProblem<dim>::postprocess(ContinuumResult& result) const {
  // Reads evaluation_point_ (the ghosted copy of the solution).
  result.dofs = dof_handler_.n_dofs();
  for (int d = 0; d < dim; ++d) result.cells[d] = prm_.cells[d] << prm_.refinements;
  result.newton_iterations = newton_iterations_;
  result.continuation_rayleigh = continuation_rayleigh_;
  const detail::FlowIntegrals integrals =
      detail::flow_integrals(dof_handler_, evaluation_point_, prm_, numbers_);
  result.nusselt = integrals.nusselt;
  result.kinetic_energy = integrals.kinetic_energy;
  result.max_speed = integrals.max_speed;
  result.temperature_mean = integrals.temperature_mean;
  result.walls = detail::wall_nusselt(dof_handler_, evaluation_point_, prm_, numbers_);
  detail::midline_maxima(dof_handler_, evaluation_point_, prm_, numbers_, result);
  std::vector<std::string> names;
  for (int d = 0; d < dim; ++d) names.push_back(std::string("u_") + "xyz"[d]);
  names.push_back("p");
  names.push_back("T");
  result.bins = detail::bin_averages(dof_handler_, evaluation_point_, names, prm_, comm_);
  // Temperature range at the owned nodes.
  double t_min = 1e300, t_max = -1e300;
  for (const auto i : solution_.block(2).locally_owned_elements()) {
    t_min = std::min(t_min, solution_.block(2)[i]);
    t_max = std::max(t_max, solution_.block(2)[i]);
  }
  result.temperature_min = dealii::Utilities::MPI::min(t_min, comm_);
  result.temperature_max = dealii::Utilities::MPI::max(t_max, comm_);
}

template <int dim>
void DistributedBoussinesqProblem<dim>::attach_fields(dealii::DataOut<dim>& data_out) const {
  std::vector<std::string> names(dim, "velocity");
  names.push_back("p");
  names.push_back("T");
  std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation> kinds(
      dim, dealii::DataComponentInterpretation::component_is_part_of_vector);
  kinds.push_back(dealii::DataComponentInterpretation::component_is_scalar);
  kinds.push_back(dealii::DataComponentInterpretation::component_is_scalar);
  data_out.attach_dof_handler(dof_handler_);
  data_out.add_data_vector(evaluation_point_, names, dealii::DataOut<dim>::type_dof_data, kinds);
  data_out.build_patches(2);
}

template <int dim>
void DistributedBoussinesqProblem<dim>::output_fields(const std::filesystem::path& dir,
                                                      ContinuumResult& result) const {
  dealii::DataOut<dim> data_out;
  attach_fields(data_out);
  detail::write_hdf5_xdmf(data_out, dir, 0.0, result.files, comm_);
}

} // namespace twinflow::continuum
