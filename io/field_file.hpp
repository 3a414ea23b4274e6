#pragma once
// Cell-centred fields on a regular grid (binned particle averages, continuum bin averages) as a
// sequence of snapshots: NAME.h5 (the data) plus NAME.xdmf (the description ParaView opens).
//
// ---------------------------------------------------------------------------------------------
// FILE LAYOUT (format_version 1). This comment is the specification; field_file.cpp follows it.
//
// NAME.h5
//   /                      attributes: format = "twinflow-fields" (string), format_version = 1
//   /grid                  group, attributes (arrays of length dim, in x, y, z order):
//                            dim (int32: 1, 2 or 3), counts (int64), origin (float64),
//                            spacing (float64)
//   /times                 float64[S]: snapshot times, strictly increasing (S snapshots)
//   /snapshots/000000      one group per snapshot, numbered 000000 ... S-1 (six digits), with
//                            attributes time (float64), wall_seconds (float64),
//                            particle_steps (int64); it holds the snapshot's fields in the
//                            order they were given (link creation order is tracked):
//     FIELD                float64[nz][ny][nx]      a scalar field, or
//                          float64[nz][ny][nx][c]   a vector field with c = dim components
//     FIELD_stderr         same shape: the standard error of FIELD (absent if none was given)
//
//   Every field dataset has rank 3 (+1 for vectors) whatever dim is: the counts of the axes a
//   grid does not have are 1. x varies fastest (C order, reversed axes), so the flat cell index
//   is i + nx * (j + ny * k) and a vector component c of cell b sits at b * dim + c: the same
//   order as particle::BinnedFields. Field names are [A-Za-z0-9_]+, not ending in "_stderr".
//
// NAME.xdmf (XDMF 2, rewritten after each snapshot)
//   A Temporal Collection of Uniform grids, one per snapshot with <Time Value=t>. Each is a
//   3DCoRectMesh (ORIGIN_DXDYDZ, z y x order) of (nz+1) x (ny+1) x (nx+1) nodes; every field is
//   an Attribute with Center="Cell" whose DataItem (Format="HDF", Dimensions equal to the
//   dataset's shape) references NAME.h5:/snapshots/NNNNNN/FIELD by a path relative to the
//   .xdmf, so the pair can be moved together. Vectors are AttributeType="Vector" (ParaView pads
//   2-component vectors with z = 0); 1-component fields are "Scalar".
//   Why always a 3D mesh: 1D and 2D grids are written as one-cell-thick 3D meshes (thickness =
//   the x spacing, at origin 0) so there is one code path and the HDF5 shapes equal the XDMF
//   shapes exactly. ParaView's Xdmf2 reader reads structured attributes through a hyperslab that
//   needs the data shape to equal the topology shape, and a 3D image of one cell thickness is
//   the best-trodden path there (a Polyline would need explicit geometry and connectivity).
//
// Crash safety: append() builds the whole NAME.h5 in memory (HDF5's core driver), writes it to
// a temporary name, closes and renames it over NAME.h5 (atomic on POSIX), then writes NAME.xdmf
// the same way (io::write_file_atomically). An interrupted or failed write (disk full) leaves
// either the previous complete pair, or a new .h5 that holds every snapshot the old .xdmf
// references, and no temporary file.
// ---------------------------------------------------------------------------------------------
//
// twinflow_io links the (parallel, openmpi) HDF5 that deal.II uses, but only ever opens files with
// the default serial driver: no MPI_Init needed, so the particle library stays free of MPI.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace twinflow::io {

// Axes d >= dim have one cell; their origin and spacing carry nothing (FieldFile stores 0 and 1).
struct Grid {
  int dim = 3;                                   // 1, 2 or 3
  std::array<std::int64_t, 3> counts{{1, 1, 1}}; // cells per axis; axes >= dim must be 1
  std::array<double, 3> origin{{0, 0, 0}};       // lower corner
  std::array<double, 3> spacing{{1, 1, 1}};      // cell edge lengths (> 0)

  std::int64_t cell_count() const { return counts[0] * counts[1] * counts[2]; }
  void validate() const; // throws std::invalid_argument
  bool operator==(const Grid& o) const {
    return dim == o.dim && counts == o.counts && origin == o.origin && spacing == o.spacing;
  }
};

// One named cell field: values[cell * components + c], cells in the grid order above.
struct Field {
  std::string name;                   // e.g. "density", "velocity"
  int components = 1;                 // 1 (scalar) or grid.dim (vector)
  std::vector<double> values;         // cell_count * components
  std::vector<double> standard_error; // same size as values, or empty if there is none
};

// Cumulative averages up to `time`.
struct Snapshot {
  double time = 0;
  double wall_seconds = 0;         // wall-clock time of the run when the snapshot was taken
  std::int64_t particle_steps = 0; // 0 for a continuum snapshot
  std::vector<Field> fields;

  const Field* find(const std::string& name) const; // nullptr if absent
};

// Writer of NAME.h5 + NAME.xdmf, holding every snapshot so far (each append rewrites both).
class FieldFile {
public:
  // Starts a new sequence: removes an earlier NAME.h5 / NAME.xdmf (a fresh run must not leave
  // an old complete-looking file next to its own). Writes nothing until the first append.
  FieldFile(std::filesystem::path path_without_extension, Grid grid);

  // Checks the snapshot against the grid (sizes, components, names, time > previous time; throws
  // std::invalid_argument) and rewrites both files atomically. Throws std::runtime_error on I/O.
  void append(Snapshot snapshot);

  const Grid& grid() const { return grid_; }
  const std::vector<Snapshot>& snapshots() const { return snapshots_; }
  std::filesystem::path h5_path() const;
  std::filesystem::path xdmf_path() const;

  struct Contents {
    Grid grid;
    std::vector<Snapshot> snapshots;
  };
  // Reads NAME.h5 (pass the .h5 path). Throws InputError naming the file and what is wrong.
  static Contents read(const std::filesystem::path& h5_path);

private:
  std::filesystem::path base_;
  Grid grid_;
  std::vector<Snapshot> snapshots_;
};

// One dataset of a plain HDF5 file (e.g. the continuum twin's mesh and solution, in deal.II's
// XDMF layout): `shape` in C order, `data` holds the product of `shape` elements.
struct Hdf5Dataset {
  enum class Type { float64, uint32 };
  std::string name;
  std::vector<std::uint64_t> shape;
  Type type = Type::float64;
  const void* data = nullptr;
};
// Writes them as one file, built in memory and stored as write_file_atomically does.
void write_hdf5_datasets(const std::filesystem::path& path,
                         const std::vector<Hdf5Dataset>& datasets);

} // namespace twinflow::io
