#pragma once
// Pieces both continuum problems share: the box mesh with boundary ids 2d (x_d = 0) and 2d+1
// (x_d = L_d), periodicity, bin averages, point values, HDF5 + XDMF output (one field, or a time
// series). Included only by the continuum's instantiation units.

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"
#include "io/field_file.hpp"
#include "io/files.hpp"

namespace twinflow::continuum::detail {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Adds the wall time of its scope to `slot`.
class ScopedTimer {
public:
  explicit ScopedTimer(double& slot) : slot_(slot), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() { slot_ += seconds_since(start_); }

private:
  double& slot_;
  std::chrono::steady_clock::time_point start_;
};

template <int dim> dealii::Point<dim> to_point(const std::array<double, 3>& x) {
  dealii::Point<dim> p;
  for (int d = 0; d < dim; ++d) p[d] = x[d];
  return p;
}

template <int dim>
void make_box_mesh(dealii::Triangulation<dim>& tria, const ContinuumParameters& prm) {
  std::vector<unsigned int> repetitions(dim);
  dealii::Point<dim> upper;
  for (int d = 0; d < dim; ++d) {
    repetitions[d] = prm.cells[d];
    upper[d] = prm.box[d];
  }
  dealii::GridGenerator::subdivided_hyper_rectangle(tria, repetitions, dealii::Point<dim>(), upper,
                                                    /*colorize=*/true);
}

// The case's initial temperature: a muparser expression in x, y, z with the constants pi, Lx,
// Ly, Lz (prm.initial_temperature, not empty).
template <int dim>
std::unique_ptr<dealii::FunctionParser<dim>>
initial_temperature_expression(const ContinuumParameters& prm) {
  const std::string variables = std::string("x,y,z").substr(0, 2 * dim - 1);
  std::map<std::string, double> constants{{"pi", M_PI}};
  for (int d = 0; d < dim; ++d) constants[std::string("L") + "xyz"[d]] = prm.box[d];
  auto f = std::make_unique<dealii::FunctionParser<dim>>(1);
  f->initialize(variables, prm.initial_temperature, constants);
  return f;
}

// Periodicity constraints first, so that wall values set afterwards stay consistent.
template <int dim>
void add_periodicity(const dealii::DoFHandler<dim>& dofs, const ContinuumParameters& prm,
                     dealii::AffineConstraints<double>& constraints) {
  for (int d = 0; d < dim; ++d)
    if (prm.boundary[d].periodic)
      dealii::DoFTools::make_periodicity_constraints(dofs, 2 * d, 2 * d + 1, d, constraints);
}

// Refine every cell once in every direction but the uniform ones (set the flags only).
template <int dim>
void flag_uniform_refinement(dealii::Triangulation<dim>& tria, const ContinuumParameters& prm) {
  dealii::RefinementCase<dim> cut = dealii::RefinementCase<dim>::no_refinement;
  for (int d = 0; d < dim; ++d)
    if (!prm.uniform_along(d)) cut = cut | dealii::RefinementCase<dim>::cut_axis(d);
  for (const auto& cell : tria.active_cell_iterators()) cell->set_refine_flag(cut);
}

template <int dim>
void refine_uniformly(dealii::Triangulation<dim>& tria, const ContinuumParameters& prm, int times) {
  for (int i = 0; i < times; ++i) {
    flag_uniform_refinement(tria, prm);
    tria.execute_coarsening_and_refinement();
  }
}

// Velocity components that no wall holds (along a periodic direction when every wall is
// free-slip): the equations fix them only up to a uniform translation, which the closed box's
// momentum (zero) would fix. In a thin slice the flow is uniform along it, so one pinned value
// is exact; other boxes keep the null space (a mean-zero condition would be needed there).
template <int dim>
void pin_free_translations(const dealii::DoFHandler<dim>& dofs, const ContinuumParameters& prm,
                           dealii::AffineConstraints<double>& constraints) {
  for (int d = 0; d < dim; ++d)
    if (!prm.boundary[d].periodic && prm.boundary[d].no_slip) return;
  for (int d = 0; d < dim; ++d) {
    if (!prm.uniform_along(d)) continue;
    const auto mask = dofs.get_fe().component_mask(dealii::FEValuesExtractors::Scalar(d));
    for (const auto i : dealii::DoFTools::extract_dofs(dofs, mask))
      if (!constraints.is_constrained(i)) {
        constraints.add_line(i);
        break;
      }
  }
}

template <int dim>
std::array<unsigned, 3> current_cells(const dealii::Triangulation<dim>& tria,
                                      const ContinuumParameters& prm) {
  std::array<unsigned, 3> cells{{1, 1, 1}};
  for (int d = 0; d < dim; ++d)
    cells[d] = prm.uniform_along(d) ? 1u : prm.cells[d] << (tria.n_levels() - 1);
  return cells;
}

// A field computed from the FE components at a point (the low-Mach density n(P, T)).
using DerivedField = std::function<double(const dealii::Vector<double>& components)>;

// The bin (x fastest) of the scene's bins that holds point x of the twin's coordinates.
template <int dim>
unsigned bin_of(const dealii::Point<dim>& x, const ContinuumParameters& prm,
                const std::array<unsigned, 3>& bins) {
  unsigned index = 0, stride = 1;
  for (int d = 0; d < dim; ++d) {
    const int i =
        std::clamp(static_cast<int>((x[d] - prm.bin_lower[d]) / prm.bin_extent(d) * bins[d]), 0,
                   static_cast<int>(bins[d]) - 1);
    index += stride * static_cast<unsigned>(i);
    stride *= bins[d];
  }
  return index;
}

// The velocity's mean over a pinned layer's strip, over its value at the twin's wall: along the
// Navier slip's line, zero a slip length ell beyond the twin's wall, the mean over depth is
// 1 - depth / (2 ell); a wall without a slip length keeps its own value (no-slip: zero anyway).
inline double strip_velocity_factor(const DirectionBoundary& b, int side, double depth) {
  const double ell = b.slip_length[side];
  return ell > 0 ? std::clamp(1 - depth / (2 * ell), 0.0, 1.0) : 1.0;
}

// Every field's integral over each bin, and each bin's volume.
struct BinSums {
  std::vector<std::vector<double>> values; // [field][bin]
  std::vector<double> volume;
  BinSums(unsigned fields, unsigned bins)
      : values(fields, std::vector<double>(bins, 0.0)), volume(bins, 0.0) {}
  // The components v (and the fields derived from them) over `weight` of volume in bin `index`.
  void add(unsigned index, double weight, const dealii::Vector<double>& v,
           const std::vector<DerivedField>& derived) {
    volume[index] += weight;
    const unsigned n = v.size();
    for (unsigned c = 0; c < n; ++c) values[c][index] += v[c] * weight;
    for (unsigned k = 0; k < derived.size(); ++k) values[n + k][index] += derived[k](v) * weight;
  }
  // The averages: the sums over every process in `comm`, over the volumes.
  std::vector<std::vector<double>> averages(const MPI_Comm comm) {
    dealii::Utilities::MPI::sum(volume, comm, volume);
    for (auto& field : values) {
      dealii::Utilities::MPI::sum(field, comm, field);
      for (std::size_t b = 0; b < field.size(); ++b) field[b] /= volume[b];
    }
    return std::move(values);
  }
};

// Adds to `sums` the strips of the scene's bins that lie beyond the twin's walls (walls moved in
// over pinned layers, continuum/twin_walls.hpp): each boundary face's values carried across its
// strip's depth. The particles' bins count the layer's particles, which the wall holds at T_wall:
// T and n take the wall's values, the velocity strip_velocity_factor's. The corners where two
// moved walls meet are left out (depth^2). Returns whether any wall was moved (the same on every
// process: it is the parameters').
template <int dim, class VectorType>
bool add_pinned_strips(const dealii::DoFHandler<dim>& dofs, const VectorType& solution,
                       const std::vector<std::string>& names, const ContinuumParameters& prm,
                       const std::vector<DerivedField>& derived, unsigned pieces,
                       const std::array<unsigned, 3>& bins, BinSums& sums) {
  std::array<std::array<double, 2>, 3> depth{};
  bool any = false;
  for (int d = 0; d < dim; ++d)
    if (prm.bin_box[d] > 0) {
      depth[d] = {{-prm.bin_lower[d], prm.bin_lower[d] + prm.bin_box[d] - prm.box[d]}};
      any = any || depth[d][0] > 1e-12 || depth[d][1] > 1e-12;
    }
  if (!any) return false;
  const auto& fe = dofs.get_fe();
  const dealii::QIterated<dim - 1> quadrature(dealii::QGauss<1>(3), pieces);
  dealii::FEFaceValues<dim> face_values(fe, quadrature,
                                        dealii::update_values | dealii::update_quadrature_points |
                                            dealii::update_JxW_values);
  const unsigned n_components = fe.n_components();
  std::vector<dealii::Vector<double>> values(quadrature.size(),
                                             dealii::Vector<double>(n_components));
  for (const auto& cell : dofs.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (unsigned f = 0; f < cell->n_faces(); ++f) {
      if (!cell->face(f)->at_boundary()) continue;
      const unsigned id = cell->face(f)->boundary_id(); // 2d: x_d = 0, 2d + 1: x_d = L_d
      const int d = static_cast<int>(id / 2), side = static_cast<int>(id % 2);
      if (d >= dim || !(depth[d][side] > 1e-12)) continue;
      const double strip = depth[d][side];
      const double u_factor = strip_velocity_factor(prm.boundary[d], side, strip);
      face_values.reinit(cell, f);
      face_values.get_function_values(solution, values);
      for (unsigned q = 0; q < quadrature.size(); ++q) {
        auto x = face_values.quadrature_point(q);
        x[d] = side == 0 ? -0.5 * strip : prm.box[d] + 0.5 * strip; // the strip's middle
        for (unsigned c = 0; c < n_components; ++c)
          if (names[c].rfind("u_", 0) == 0) values[q][c] *= u_factor;
        sums.add(bin_of(x, prm, bins), face_values.JxW(q) * strip, values[q], derived);
      }
    }
  }
  return true;
}

// Sub-cell pieces per cell direction for the bins' quadrature: a cell straddling a bin face is
// split into pieces no larger than a quarter bin.
template <int dim>
unsigned sub_cell_pieces(const dealii::DoFHandler<dim>& dofs, const ContinuumParameters& prm,
                         const std::array<unsigned, 3>& bins, const MPI_Comm comm) {
  double finest_bin = 1e300, largest_cell = 0;
  for (int d = 0; d < dim; ++d) finest_bin = std::min(finest_bin, prm.bin_extent(d) / bins[d]);
  for (const auto& cell : dofs.active_cell_iterators())
    largest_cell = std::max(largest_cell, cell->diameter());
  largest_cell = dealii::Utilities::MPI::max(largest_cell, comm);
  return std::clamp(static_cast<unsigned>(std::ceil(4 * largest_cell / finest_bin)), 1u, 16u);
}

// Average of every FE component over a regular grid of bins covering the box: the integral over
// each bin divided by its volume. Quadrature points are assigned to the bin that contains them;
// the sub-cell quadrature is iterated (sub_cell_pieces: error of a non-aligned bin face O(h_sub /
// bin width)). Cells not owned by this process are skipped and the sums added over `comm` (the
// distributed solver); VectorType: dealii::Vector or a ghosted Trilinos vector. `derived` adds
// fields computed from the components at each quadrature point (the low-Mach density n(P, T)),
// after the components, named after them in `names`. Beside walls moved in over pinned layers
// the scene's bins also count the layers' strips (add_pinned_strips); the twin's own fields over
// its domain alone are kept beside them (BinAverages::domain_values).
template <int dim, class VectorType>
BinAverages bin_averages(const dealii::DoFHandler<dim>& dofs, const VectorType& solution,
                         const std::vector<std::string>& names, const ContinuumParameters& prm,
                         const MPI_Comm comm = MPI_COMM_SELF,
                         const std::vector<DerivedField>& derived = {}) {
  BinAverages out;
  out.names = names;
  unsigned n_bins = 1;
  for (int d = 0; d < dim; ++d) {
    out.bins[d] = std::max(1u, prm.bins[d]);
    n_bins *= out.bins[d];
  }
  const unsigned pieces = sub_cell_pieces(dofs, prm, out.bins, comm);
  const dealii::QIterated<dim> quadrature(dealii::QGauss<1>(3), pieces);
  const auto& fe = dofs.get_fe();
  dealii::FEValues<dim> fe_values(fe, quadrature,
                                  dealii::update_values | dealii::update_quadrature_points |
                                      dealii::update_JxW_values);
  std::vector<dealii::Vector<double>> values(quadrature.size(),
                                             dealii::Vector<double>(fe.n_components()));
  BinSums sums(fe.n_components() + static_cast<unsigned>(derived.size()), n_bins);
  for (const auto& cell : dofs.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    fe_values.get_function_values(solution, values);
    for (unsigned q = 0; q < quadrature.size(); ++q)
      sums.add(bin_of(fe_values.quadrature_point(q), prm, out.bins), fe_values.JxW(q), values[q],
               derived);
  }
  BinSums domain = sums;
  if (add_pinned_strips(dofs, solution, names, prm, derived, pieces, out.bins, sums))
    out.domain_values = domain.averages(comm);
  out.values = sums.averages(comm);
  return out;
}

template <int dim>
void probe(const dealii::DoFHandler<dim>& dofs, const dealii::Vector<double>& solution,
           const ContinuumParameters& prm, ContinuumResult& result) {
  result.probe_points = prm.probe_points;
  for (const auto& x : prm.probe_points) {
    dealii::Vector<double> value(dofs.get_fe().n_components());
    dealii::VectorTools::point_value(dofs, solution, to_point<dim>(x), value);
    result.probe_values.emplace_back(value.begin(), value.end());
  }
}

// The mesh and solution of `filter` as deal.II's write_hdf5_parallel lays them out (datasets
// "nodes", "cells" and one per data set, which create_xdmf_entry references). One process: built
// in memory and written by io::write_hdf5_datasets (temporary name, renamed when complete, every
// HDF5 handle closed on every path: a full disk is an io::OutputError naming the file and the
// reason, never a half-written file or a crash at MPI_Finalize). Several processes: deal.II's
// collective writer into a temporary name, renamed by the root.
inline void write_filtered_hdf5(
    const dealii::DataOutBase::DataOutFilter& filter, bool with_mesh,
    const std::filesystem::path& mesh_file, const std::filesystem::path& solution_file,
    int spacedim,
    const std::function<void(const std::string&, const std::string&)>& parallel_writer,
    const MPI_Comm comm) {
  if (dealii::Utilities::MPI::n_mpi_processes(comm) > 1) {
    std::filesystem::path mesh_tmp = mesh_file, solution_tmp = solution_file;
    mesh_tmp += ".tmp", solution_tmp += ".tmp";
    parallel_writer(mesh_tmp.string(), solution_tmp.string());
    if (dealii::Utilities::MPI::this_mpi_process(comm) == 0) {
      if (with_mesh) std::filesystem::rename(mesh_tmp, mesh_file);
      if (!with_mesh || solution_file != mesh_file)
        std::filesystem::rename(solution_tmp, solution_file);
    }
    return;
  }
  using io::Hdf5Dataset;
  std::vector<Hdf5Dataset> mesh, solution;
  std::vector<double> nodes;
  std::vector<unsigned int> cells;
  if (with_mesh) {
    filter.fill_node_data(nodes);
    filter.fill_cell_data(0, cells);
    const std::uint64_t n_nodes = filter.n_nodes(), n_cells = filter.n_cells();
    const std::uint64_t node_columns = spacedim < 2 ? 2 : spacedim;
    mesh.push_back({"nodes", {n_nodes, node_columns}, Hdf5Dataset::Type::float64, nodes.data()});
    mesh.push_back({"cells",
                    {n_cells, n_cells ? cells.size() / n_cells : 0},
                    Hdf5Dataset::Type::uint32,
                    cells.data()});
  }
  std::vector<Hdf5Dataset>& data = solution_file == mesh_file ? mesh : solution;
  for (unsigned i = 0; i < filter.n_data_sets(); ++i)
    data.push_back({filter.get_data_set_name(i),
                    {static_cast<std::uint64_t>(filter.n_nodes()), filter.get_data_set_dim(i)},
                    Hdf5Dataset::Type::float64,
                    filter.get_data_set(i)});
  if (solution_file != mesh_file) io::write_hdf5_datasets(solution_file, solution);
  if (with_mesh) io::write_hdf5_datasets(mesh_file, mesh);
}

// The XDMF file ParaView opens, as DataOutInterface::write_xdmf_file writes it; root only.
template <int dim>
void write_xdmf(const std::vector<dealii::XDMFEntry>& entries, const std::filesystem::path& file,
                const MPI_Comm comm) {
  if (dealii::Utilities::MPI::this_mpi_process(comm) != 0) return;
  std::string text = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
                     "<Xdmf Version=\"2.0\">\n  <Domain>\n    <Grid Name=\"CellTime\" "
                     "GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& entry : entries)
    text += entry.get_xdmf_content(3, dealii::ReferenceCells::get_hypercube<dim>());
  text += "    </Grid>\n  </Domain>\n</Xdmf>\n";
  io::write_file_atomically(file, text);
}

// fields.h5 (mesh and solution) + fields.xdmf, each complete under its name or not there.
template <int dim>
void write_hdf5_xdmf(const dealii::DataOut<dim>& data_out, const std::filesystem::path& dir,
                     double time, std::vector<std::string>& files,
                     const MPI_Comm comm = MPI_COMM_SELF) {
  dealii::DataOutBase::DataOutFilter filter(
      dealii::DataOutBase::DataOutFilterFlags(/*filter_duplicate_vertices=*/true,
                                              /*xdmf_hdf5_output=*/true));
  data_out.write_filtered_data(filter);
  const std::string h5 = "fields.h5", xdmf = "fields.xdmf";
  write_filtered_hdf5(
      filter, true, dir / h5, dir / h5, dim,
      [&](const std::string& mesh, const std::string&) {
        data_out.write_hdf5_parallel(filter, mesh, comm);
      },
      comm);
  const std::vector<dealii::XDMFEntry> entries{data_out.create_xdmf_entry(filter, h5, time, comm)};
  write_xdmf<dim>(entries, dir / xdmf, comm);
  files.push_back(h5);
  files.push_back(xdmf);
}

// Field snapshots of a run in time, as a series ParaView opens with its time controls: the mesh
// once (fields_mesh.h5: it does not change), one solution file per snapshot (fields_NNNN.h5) and
// fields.xdmf, a temporal collection of all snapshots so far, rewritten (atomically) after each.
template <int dim> class FieldSeriesWriter {
public:
  FieldSeriesWriter(std::filesystem::path dir, const MPI_Comm comm = MPI_COMM_SELF)
      : dir_(std::move(dir)), comm_(comm) {}

  void write(const dealii::DataOut<dim>& data_out, double time, std::vector<std::string>& files) {
    dealii::DataOutBase::DataOutFilter filter(
        dealii::DataOutBase::DataOutFilterFlags(/*filter_duplicate_vertices=*/true,
                                                /*xdmf_hdf5_output=*/true));
    data_out.write_filtered_data(filter);
    const bool first = entries_.empty();
    const std::string mesh = "fields_mesh.h5";
    const std::string solution =
        "fields_" + dealii::Utilities::int_to_string(entries_.size(), 4) + ".h5";
    write_filtered_hdf5(
        filter, first, dir_ / mesh, dir_ / solution, dim,
        [&](const std::string& mesh_tmp, const std::string& solution_tmp) {
          data_out.write_hdf5_parallel(filter, first, mesh_tmp, solution_tmp, comm_);
        },
        comm_);
    entries_.push_back(data_out.create_xdmf_entry(filter, mesh, solution, time, comm_));
    write_xdmf<dim>(entries_, dir_ / "fields.xdmf", comm_);
    if (first) files.push_back(mesh), files.push_back("fields.xdmf");
    files.push_back(solution);
  }

private:
  std::filesystem::path dir_;
  MPI_Comm comm_;
  std::vector<dealii::XDMFEntry> entries_;
};

} // namespace twinflow::continuum::detail
