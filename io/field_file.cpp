#include "io/field_file.hpp"

#include <hdf5.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "io/files.hpp"

namespace twinflow::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormatName = "twinflow-fields";
constexpr int kFormatVersion = 1;
constexpr const char* kStderrSuffix = "_stderr";

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Names become HDF5 link names and XML attribute values: keep them plain.
bool is_plain_name(const std::string& name) {
  if (name.empty()) return false;
  for (char ch : name) {
    bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
              ch == '_';
    if (!ok) return false;
  }
  return true;
}

std::string snapshot_group_name(std::size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06zu", index);
  return buf;
}

// Dataset shape (C order, x fastest): nz, ny, nx [, components].
std::vector<hsize_t> field_shape(const Grid& grid, int components) {
  std::vector<hsize_t> shape{static_cast<hsize_t>(grid.counts[2]),
                             static_cast<hsize_t>(grid.counts[1]),
                             static_cast<hsize_t>(grid.counts[0])};
  if (components > 1) shape.push_back(static_cast<hsize_t>(components));
  return shape;
}

// ---- HDF5 plumbing -----------------------------------------------------------------------------

// Owns one HDF5 identifier; `close` is H5Fclose, H5Gclose, ...
class Hid {
public:
  Hid(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  ~Hid() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now and reports failure (a file's close is where buffered data reaches the disk).
  bool close() {
    herr_t status = id_ >= 0 ? close_(id_) : -1;
    id_ = -1;
    return status >= 0;
  }

private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// HDF5 prints its error stack to stderr by default; we report errors ourselves.
class QuietHdf5Errors {
public:
  QuietHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;
  ~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// ---- writing -----------------------------------------------------------------------------------

class Writer {
public:
  explicit Writer(fs::path path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path_.string() + ": HDF5 error building " + what + " (in memory)");
  }
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) fail(what);
    return id;
  }
  void check(herr_t status, const std::string& what) const {
    if (status < 0) fail(what);
  }

  template <class T>
  void attribute(hid_t loc, const char* name, hid_t type, const std::vector<T>& values) const {
    hsize_t n = values.size();
    Hid space(check(H5Screate_simple(1, &n, nullptr), name), H5Sclose);
    Hid attr(check(H5Acreate2(loc, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), name),
             H5Aclose);
    check(H5Awrite(attr.get(), type, values.data()), name);
  }
  template <class T> void scalar_attribute(hid_t loc, const char* name, hid_t type, T value) const {
    Hid space(check(H5Screate(H5S_SCALAR), name), H5Sclose);
    Hid attr(check(H5Acreate2(loc, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), name),
             H5Aclose);
    check(H5Awrite(attr.get(), type, &value), name);
  }
  void string_attribute(hid_t loc, const char* name, const std::string& value) const {
    Hid type(check(H5Tcopy(H5T_C_S1), name), H5Tclose);
    check(H5Tset_size(type.get(), value.size()), name);
    Hid space(check(H5Screate(H5S_SCALAR), name), H5Sclose);
    Hid attr(check(H5Acreate2(loc, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), name),
             H5Aclose);
    check(H5Awrite(attr.get(), type.get(), value.data()), name);
  }
  void dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& shape,
               const double* data) const {
    dataset(loc, name, shape, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data);
  }
  void dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& shape,
               hid_t file_type, hid_t memory_type, const void* data) const {
    Hid space(check(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr), name),
              H5Sclose);
    Hid set(check(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                             H5P_DEFAULT),
                  name),
            H5Dclose);
    check(H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), name);
  }

private:
  fs::path path_;
};

// An HDF5 file built in memory by the core driver (no backing store): HDF5 itself never touches
// the disk, so a full disk cannot leave it with a half-written file or with handles still open
// at MPI_Finalize; every handle is an Hid, closed on every path, exceptions included. Returns
// the file's bytes, which write_file_atomically stores (temporary name, rename when complete).
template <class Fill> std::string h5_image(const fs::path& path, Fill&& fill) {
  QuietHdf5Errors quiet;
  Writer w(path);
  Hid fapl(w.check(H5Pcreate(H5P_FILE_ACCESS), "file access properties"), H5Pclose);
  w.check(H5Pset_fapl_core(fapl.get(), 1 << 20, /*backing_store=*/0), "core driver");
  static std::atomic<unsigned> images{0}; // HDF5 refuses to create a file it holds open
  const std::string name = path.string() + ".image." + std::to_string(images++);
  Hid file(w.check(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), "file"),
           H5Fclose);
  fill(w, file.get());
  w.check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "file (flush)");
  const ssize_t size = H5Fget_file_image(file.get(), nullptr, 0);
  if (size < 0) w.fail("file (image size)");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (H5Fget_file_image(file.get(), bytes.data(), bytes.size()) != size) w.fail("file (image)");
  if (!file.close()) w.fail("file (close)");
  return bytes;
}

void fill_h5(const Writer& w, hid_t file, const Grid& grid,
             const std::vector<Snapshot>& snapshots) {
  w.string_attribute(file, "format", kFormatName);
  w.scalar_attribute(file, "format_version", H5T_NATIVE_INT, kFormatVersion);
  {
    Hid g(w.check(H5Gcreate2(file, "grid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "/grid"),
          H5Gclose);
    const auto d = static_cast<std::size_t>(grid.dim);
    w.scalar_attribute(g.get(), "dim", H5T_NATIVE_INT, grid.dim);
    w.attribute(g.get(), "counts", H5T_NATIVE_INT64,
                std::vector<std::int64_t>(grid.counts.begin(), grid.counts.begin() + d));
    w.attribute(g.get(), "origin", H5T_NATIVE_DOUBLE,
                std::vector<double>(grid.origin.begin(), grid.origin.begin() + d));
    w.attribute(g.get(), "spacing", H5T_NATIVE_DOUBLE,
                std::vector<double>(grid.spacing.begin(), grid.spacing.begin() + d));
  }
  std::vector<double> times;
  for (const Snapshot& s : snapshots) times.push_back(s.time);
  w.dataset(file, "times", {static_cast<hsize_t>(times.size())}, times.data());

  Hid all(
      w.check(H5Gcreate2(file, "snapshots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "/snapshots"),
      H5Gclose);
  // Track link creation order so the reader returns the fields in the order they were given.
  Hid ordered(w.check(H5Pcreate(H5P_GROUP_CREATE), "group properties"), H5Pclose);
  w.check(H5Pset_link_creation_order(ordered.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
          "group properties");
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    const Snapshot& s = snapshots[i];
    const std::string name = snapshot_group_name(i);
    Hid g(w.check(H5Gcreate2(all.get(), name.c_str(), H5P_DEFAULT, ordered.get(), H5P_DEFAULT),
                  "/snapshots/" + name),
          H5Gclose);
    w.scalar_attribute(g.get(), "time", H5T_NATIVE_DOUBLE, s.time);
    w.scalar_attribute(g.get(), "wall_seconds", H5T_NATIVE_DOUBLE, s.wall_seconds);
    w.scalar_attribute(g.get(), "particle_steps", H5T_NATIVE_INT64, s.particle_steps);
    for (const Field& f : s.fields) {
      const auto shape = field_shape(grid, f.components);
      w.dataset(g.get(), f.name, shape, f.values.data());
      if (!f.standard_error.empty())
        w.dataset(g.get(), f.name + kStderrSuffix, shape, f.standard_error.data());
    }
  }
}

// ---- XDMF --------------------------------------------------------------------------------------

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    const char* entity = ch == '&'    ? "&amp;"
                         : ch == '<'  ? "&lt;"
                         : ch == '>'  ? "&gt;"
                         : ch == '"'  ? "&quot;"
                         : ch == '\'' ? "&apos;"
                                      : nullptr;
    if (entity)
      out += entity;
    else
      out += ch;
  }
  return out;
}

std::string join(const std::vector<hsize_t>& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? " " : "") + std::to_string(v[i]);
  return out;
}

std::string xdmf_text(const Grid& grid, const std::vector<Snapshot>& snapshots,
                      const std::string& h5_name) {
  std::ostringstream x;
  x.imbue(std::locale::classic());
  x.precision(17); // round-trips doubles
  // Axes the grid does not have become one cell of the x spacing's thickness (see header).
  std::array<double, 3> origin{{0, 0, 0}},
      spacing{{grid.spacing[0], grid.spacing[0], grid.spacing[0]}};
  for (int d = 0; d < grid.dim; ++d) origin[d] = grid.origin[d], spacing[d] = grid.spacing[d];
  const std::string file_ref = xml_escape(h5_name);

  x << "<?xml version=\"1.0\" ?>\n"
    << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"2.0\">\n"
    << "  <Domain>\n"
    << "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    const Snapshot& s = snapshots[i];
    const std::string group = snapshot_group_name(i);
    x << "      <Grid Name=\"snapshot_" << group << "\" GridType=\"Uniform\">\n"
      << "        <Time Value=\"" << s.time << "\"/>\n"
      << "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << grid.counts[2] + 1
      << " " << grid.counts[1] + 1 << " " << grid.counts[0] + 1 << "\"/>\n"
      << "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
      << "          <DataItem Name=\"Origin\" Dimensions=\"3\" NumberType=\"Float\" "
         "Precision=\"8\" Format=\"XML\">"
      << origin[2] << " " << origin[1] << " " << origin[0] << "</DataItem>\n"
      << "          <DataItem Name=\"Spacing\" Dimensions=\"3\" NumberType=\"Float\" "
         "Precision=\"8\" Format=\"XML\">"
      << spacing[2] << " " << spacing[1] << " " << spacing[0] << "</DataItem>\n"
      << "        </Geometry>\n";
    auto attribute = [&](const std::string& name, int components) {
      x << "        <Attribute Name=\"" << name << "\" AttributeType=\""
        << (components > 1 ? "Vector" : "Scalar") << "\" Center=\"Cell\">\n"
        << "          <DataItem Dimensions=\"" << join(field_shape(grid, components))
        << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file_ref << ":/snapshots/"
        << group << "/" << name << "</DataItem>\n"
        << "        </Attribute>\n";
    };
    for (const Field& f : s.fields) {
      attribute(f.name, f.components);
      if (!f.standard_error.empty()) attribute(f.name + kStderrSuffix, f.components);
    }
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n"
    << "  </Domain>\n"
    << "</Xdmf>\n";
  return x.str();
}

// ---- reading -----------------------------------------------------------------------------------

class Reader {
public:
  explicit Reader(fs::path path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_.string() + ": " + what);
  }
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) fail("cannot read " + what);
    return id;
  }

  std::vector<hsize_t> shape(hid_t loc, const std::string& what, bool attribute) const {
    Hid space(check(attribute ? H5Aget_space(loc) : H5Dget_space(loc), what), H5Sclose);
    int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 0) fail("cannot read the shape of " + what);
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    if (rank > 0 && H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0)
      fail("cannot read the shape of " + what);
    return dims;
  }
  static std::size_t element_count(const std::vector<hsize_t>& dims) {
    std::size_t n = 1;
    for (hsize_t d : dims) n *= static_cast<std::size_t>(d);
    return n;
  }

  // Numeric attribute of any rank, converted to T by HDF5.
  template <class T>
  std::vector<T> attribute(hid_t loc, const std::string& where, const char* name,
                           hid_t memtype) const {
    const std::string what = "attribute " + where + "@" + std::string(name);
    if (H5Aexists(loc, name) <= 0) fail("missing " + what);
    Hid attr(check(H5Aopen(loc, name, H5P_DEFAULT), what), H5Aclose);
    std::vector<T> values(element_count(shape(attr.get(), what, true)));
    if (H5Aread(attr.get(), memtype, values.data()) < 0) fail("cannot read " + what);
    return values;
  }
  template <class T>
  T scalar_attribute(hid_t loc, const std::string& where, const char* name, hid_t memtype) const {
    auto v = attribute<T>(loc, where, name, memtype);
    if (v.size() != 1) fail("attribute " + where + "@" + name + " is not a single value");
    return v[0];
  }
  std::string string_attribute(hid_t loc, const std::string& where, const char* name) const {
    const std::string what = "attribute " + where + "@" + std::string(name);
    if (H5Aexists(loc, name) <= 0) fail("missing " + what);
    Hid attr(check(H5Aopen(loc, name, H5P_DEFAULT), what), H5Aclose);
    Hid type(check(H5Aget_type(attr.get()), what), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) != 0)
      fail(what + " is not a fixed-length string");
    std::string value(H5Tget_size(type.get()), '\0');
    if (H5Aread(attr.get(), type.get(), value.data()) < 0) fail("cannot read " + what);
    return value.substr(0, value.find('\0'));
  }
  std::vector<double> dataset(hid_t loc, const std::string& name, const std::string& where,
                              std::vector<hsize_t>* dims_out) const {
    const std::string what = "dataset " + where + "/" + name;
    Hid set(check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), what), H5Dclose);
    auto dims = shape(set.get(), what, false);
    std::vector<double> values(element_count(dims));
    if (!values.empty() &&
        H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
      fail("cannot read " + what);
    if (dims_out) *dims_out = std::move(dims);
    return values;
  }

private:
  fs::path path_;
};

} // namespace

// ---- public ------------------------------------------------------------------------------------

std::string hdf5_version() {
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);
  return "HDF5 " + std::to_string(major) + "." + std::to_string(minor) + "." +
         std::to_string(release);
}

void Grid::validate() const {
  if (dim < 1 || dim > 3) throw std::invalid_argument("Grid: dim must be 1, 2 or 3");
  for (int d = 0; d < 3; ++d) {
    if (counts[d] < 1) throw std::invalid_argument("Grid: cell counts must be >= 1");
    if (d >= dim && counts[d] != 1)
      throw std::invalid_argument("Grid: axes beyond dim must have a count of 1");
    if (d < dim && !(std::isfinite(spacing[d]) && spacing[d] > 0 && std::isfinite(origin[d])))
      throw std::invalid_argument("Grid: spacing must be finite and > 0, origin finite");
  }
}

const Field* Snapshot::find(const std::string& name) const {
  for (const Field& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

FieldFile::FieldFile(fs::path path_without_extension, Grid grid)
    : base_(std::move(path_without_extension)), grid_(grid) {
  grid_.validate();
  // Unused axes carry no information: normalise them so that read() returns an equal Grid.
  for (int d = grid_.dim; d < 3; ++d) grid_.origin[d] = 0, grid_.spacing[d] = 1;
  std::error_code ignored;
  fs::remove(h5_path(), ignored);
  fs::remove(xdmf_path(), ignored);
  fs::path stale = h5_path(); // what earlier versions wrote before renaming (a killed run's)
  stale += ".tmp";
  fs::remove(stale, ignored);
}

fs::path FieldFile::h5_path() const {
  fs::path p = base_;
  p += ".h5";
  return p;
}

fs::path FieldFile::xdmf_path() const {
  fs::path p = base_;
  p += ".xdmf";
  return p;
}

void FieldFile::append(Snapshot snapshot) {
  const std::string where = "FieldFile " + h5_path().string() + ": snapshot at time " +
                            std::to_string(snapshot.time) + ": ";
  if (!std::isfinite(snapshot.time)) throw std::invalid_argument(where + "time must be finite");
  if (!snapshots_.empty() && !(snapshot.time > snapshots_.back().time))
    throw std::invalid_argument(where + "times must increase strictly");
  const auto cells = static_cast<std::size_t>(grid_.cell_count());
  for (std::size_t i = 0; i < snapshot.fields.size(); ++i) {
    const Field& f = snapshot.fields[i];
    const std::string field = where + "field '" + f.name + "': ";
    if (!is_plain_name(f.name) || ends_with(f.name, kStderrSuffix))
      throw std::invalid_argument(field + "names are [A-Za-z0-9_]+ and do not end in _stderr");
    for (std::size_t j = 0; j < i; ++j)
      if (snapshot.fields[j].name == f.name) throw std::invalid_argument(field + "given twice");
    if (f.components != 1 && f.components != grid_.dim)
      throw std::invalid_argument(field + "components must be 1 or the grid's dim");
    const std::size_t expected = cells * static_cast<std::size_t>(f.components);
    if (f.values.size() != expected)
      throw std::invalid_argument(field + "has " + std::to_string(f.values.size()) +
                                  " values, the grid needs " + std::to_string(expected));
    if (!f.standard_error.empty() && f.standard_error.size() != expected)
      throw std::invalid_argument(field + "standard_error has " +
                                  std::to_string(f.standard_error.size()) + " values, needs " +
                                  std::to_string(expected));
  }
  snapshots_.push_back(std::move(snapshot));
  try {
    // The .h5 first: it always holds every snapshot the .xdmf beside it references.
    write_file_atomically(h5_path(), h5_image(h5_path(), [&](const Writer& w, hid_t file) {
                            fill_h5(w, file, grid_, snapshots_);
                          }));
    write_file_atomically(xdmf_path(), xdmf_text(grid_, snapshots_, h5_path().filename().string()));
  } catch (...) {
    snapshots_.pop_back(); // the files still describe the earlier snapshots
    throw;
  }
}

void write_hdf5_datasets(const fs::path& path, const std::vector<Hdf5Dataset>& datasets) {
  write_file_atomically(
      path, h5_image(path, [&](const Writer& w, hid_t file) {
        for (const Hdf5Dataset& d : datasets) {
          std::vector<hsize_t> shape(d.shape.begin(), d.shape.end());
          if (d.type == Hdf5Dataset::Type::float64)
            w.dataset(file, d.name, shape, H5T_NATIVE_DOUBLE, H5T_NATIVE_DOUBLE, d.data);
          else
            w.dataset(file, d.name, shape, H5T_NATIVE_UINT, H5T_NATIVE_UINT, d.data);
        }
      }));
}

namespace {

Grid read_grid(const Reader& r, hid_t file) {
  if (H5Lexists(file, "grid", H5P_DEFAULT) <= 0) r.fail("missing group /grid");
  Hid g(r.check(H5Gopen2(file, "grid", H5P_DEFAULT), "group /grid"), H5Gclose);
  Grid grid;
  grid.dim = r.scalar_attribute<int>(g.get(), "/grid", "dim", H5T_NATIVE_INT);
  if (grid.dim < 1 || grid.dim > 3) r.fail("/grid@dim is not 1, 2 or 3");
  const auto d = static_cast<std::size_t>(grid.dim);
  auto counts = r.attribute<std::int64_t>(g.get(), "/grid", "counts", H5T_NATIVE_INT64);
  auto origin = r.attribute<double>(g.get(), "/grid", "origin", H5T_NATIVE_DOUBLE);
  auto spacing = r.attribute<double>(g.get(), "/grid", "spacing", H5T_NATIVE_DOUBLE);
  if (counts.size() != d || origin.size() != d || spacing.size() != d)
    r.fail("/grid@counts, origin and spacing must have dim entries");
  for (std::size_t k = 0; k < d; ++k)
    grid.counts[k] = counts[k], grid.origin[k] = origin[k], grid.spacing[k] = spacing[k];
  try {
    grid.validate();
  } catch (const std::invalid_argument& e) {
    r.fail(std::string("/grid: ") + e.what());
  }
  return grid;
}

// The group's links in creation order: the order the writer added the fields.
std::vector<std::string> link_names(const Reader& r, hid_t group, const std::string& where) {
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0) r.fail("cannot list " + where);
  std::vector<std::string> names;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    ssize_t length =
        H5Lget_name_by_idx(group, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (length < 0) r.fail("cannot list " + where + " in creation order");
    std::string name(static_cast<std::size_t>(length) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, k, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(length));
    names.push_back(std::move(name));
  }
  return names;
}

// A field, or the standard error of the field written just before it.
void add_dataset(const Reader& r, const Grid& grid, hid_t group, const std::string& where,
                 const std::string& name, Snapshot& s) {
  std::vector<hsize_t> dims;
  std::vector<double> values = r.dataset(group, name, where, &dims);
  const std::string what = "dataset " + where + "/" + name;
  int components = dims.size() == 4 ? static_cast<int>(dims[3]) : 1;
  if ((dims.size() != 3 && dims.size() != 4) || field_shape(grid, components) != dims ||
      (components != 1 && components != grid.dim))
    r.fail(what + " has shape [" + join(dims) + "], the grid needs [" + join(field_shape(grid, 1)) +
           "] (+ [dim] for vectors)");
  if (!ends_with(name, kStderrSuffix)) {
    s.fields.push_back(Field{name, components, std::move(values), {}});
    return;
  }
  const std::string base = name.substr(0, name.size() - std::string(kStderrSuffix).size());
  Field* f = nullptr;
  for (Field& candidate : s.fields)
    if (candidate.name == base) f = &candidate;
  if (!f || !f->standard_error.empty() || f->components != components)
    r.fail(what + " does not match a field " + base + " written before it");
  f->standard_error = std::move(values);
}

Snapshot read_snapshot(const Reader& r, const Grid& grid, hid_t snapshots, std::size_t i,
                       double time) {
  const std::string name = snapshot_group_name(i);
  const std::string where = "/snapshots/" + name;
  if (H5Lexists(snapshots, name.c_str(), H5P_DEFAULT) <= 0) r.fail("missing group " + where);
  Hid g(r.check(H5Gopen2(snapshots, name.c_str(), H5P_DEFAULT), "group " + where), H5Gclose);
  Snapshot s;
  s.time = r.scalar_attribute<double>(g.get(), where, "time", H5T_NATIVE_DOUBLE);
  s.wall_seconds = r.scalar_attribute<double>(g.get(), where, "wall_seconds", H5T_NATIVE_DOUBLE);
  s.particle_steps =
      r.scalar_attribute<std::int64_t>(g.get(), where, "particle_steps", H5T_NATIVE_INT64);
  if (!(s.time == time)) r.fail(where + "@time differs from /times[" + std::to_string(i) + "]");
  for (const std::string& dataset : link_names(r, g.get(), where))
    add_dataset(r, grid, g.get(), where, dataset, s);
  return s;
}

} // namespace

FieldFile::Contents FieldFile::read(const fs::path& h5_path) {
  QuietHdf5Errors quiet;
  Reader r(h5_path);
  if (!fs::exists(h5_path)) r.fail("no such file");
  if (H5Fis_hdf5(h5_path.c_str()) <= 0) r.fail("not an HDF5 file (truncated or corrupt?)");
  Hid file(r.check(H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "the file"), H5Fclose);
  if (r.string_attribute(file.get(), "/", "format") != kFormatName)
    r.fail("not a twinflow field file (attribute /@format)");
  const int version = r.scalar_attribute<int>(file.get(), "/", "format_version", H5T_NATIVE_INT);
  if (version != kFormatVersion)
    r.fail("format_version " + std::to_string(version) + " is not supported (this build reads " +
           std::to_string(kFormatVersion) + ")");

  Contents c;
  c.grid = read_grid(r, file.get());
  if (H5Lexists(file.get(), "times", H5P_DEFAULT) <= 0) r.fail("missing dataset /times");
  const std::vector<double> times = r.dataset(file.get(), "times", "", nullptr);
  if (H5Lexists(file.get(), "snapshots", H5P_DEFAULT) <= 0) r.fail("missing group /snapshots");
  Hid all(r.check(H5Gopen2(file.get(), "snapshots", H5P_DEFAULT), "group /snapshots"), H5Gclose);
  H5G_info_t all_info;
  if (H5Gget_info(all.get(), &all_info) < 0) r.fail("cannot list /snapshots");
  if (all_info.nlinks != times.size())
    r.fail("/snapshots has " + std::to_string(all_info.nlinks) + " groups but /times " +
           std::to_string(times.size()) + " entries");
  for (std::size_t i = 0; i < times.size(); ++i)
    c.snapshots.push_back(read_snapshot(r, c.grid, all.get(), i, times[i]));
  return c;
}

} // namespace twinflow::io
