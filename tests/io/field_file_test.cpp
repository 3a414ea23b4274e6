// FieldFile: HDF5 round trip, the XDMF side file (well-formed, referencing existing datasets of
// the declared shapes), h5py compatibility, crash safety and input checks. Runs without MPI: the
// parallel HDF5 library must work with the serial driver and no MPI_Init.
#include "io/field_file.hpp"

#include <hdf5.h>

#include <gtest/gtest.h>

#include "helpers.hpp"
#include "io/files.hpp"
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

namespace fs = std::filesystem;
using twinflow::io::Field;
using twinflow::io::FieldFile;
using twinflow::io::Grid;
using twinflow::io::InputError;
using twinflow::io::Snapshot;
using twinflow::io::testing::input_error_of;
using twinflow::io::testing::ScratchDirTest;

namespace {

Grid make_grid(int dim) {
  Grid g;
  g.dim = dim;
  g.counts = {{5, dim >= 2 ? 4 : 1, dim == 3 ? 3 : 1}};
  g.origin = {{-1.0, 0.25, 2.0}};
  g.spacing = {{0.5, 0.125, 1.0 / 3.0}};
  if (dim < 3) g.origin[2] = 0, g.spacing[2] = 1;
  if (dim < 2) g.origin[1] = 0, g.spacing[1] = 1;
  return g;
}

// Distinct values per snapshot, field, cell and component (so mix-ups show).
std::vector<double> pattern(const Grid& g, int components, double seed) {
  std::vector<double> v(static_cast<std::size_t>(g.cell_count() * components));
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = seed + 0.001 * static_cast<double>(i);
  return v;
}

Snapshot make_snapshot(const Grid& g, int index) {
  Snapshot s;
  s.time = 10.0 * (index + 1);
  s.wall_seconds = 1.5 * (index + 1);
  s.particle_steps = 1000 * (index + 1);
  const double k = 100.0 * index;
  s.fields.push_back({"density", 1, pattern(g, 1, k + 1), pattern(g, 1, k + 2)});
  s.fields.push_back({"temperature_kinetic", 1, pattern(g, 1, k + 3), pattern(g, 1, k + 4)});
  s.fields.push_back({"velocity", g.dim, pattern(g, g.dim, k + 5), pattern(g, g.dim, k + 6)});
  s.fields.push_back({"cell_volume", 1, pattern(g, 1, k + 7), {}}); // no standard error
  return s;
}

void expect_same(const Snapshot& a, const Snapshot& b) {
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.wall_seconds, b.wall_seconds);
  EXPECT_EQ(a.particle_steps, b.particle_steps);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (std::size_t i = 0; i < a.fields.size(); ++i) {
    EXPECT_EQ(a.fields[i].name, b.fields[i].name);
    EXPECT_EQ(a.fields[i].components, b.fields[i].components);
    EXPECT_EQ(a.fields[i].values, b.fields[i].values) << a.fields[i].name;
    EXPECT_EQ(a.fields[i].standard_error, b.fields[i].standard_error) << a.fields[i].name;
  }
}

// ---- a minimal, strict XML reader: enough to prove well-formedness and walk the XDMF ------------

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::vector<XmlElement> children;
  std::string text;
  std::vector<const XmlElement*> all(const std::string& child_name) const {
    std::vector<const XmlElement*> out;
    for (const XmlElement& c : children)
      if (c.name == child_name) out.push_back(&c);
    return out;
  }
};

class XmlParser {
public:
  explicit XmlParser(std::string text) : s_(std::move(text)) {}
  XmlElement document() {
    skip_space();
    if (s_.compare(pos_, 5, "<?xml") == 0) skip_past("?>");
    skip_space();
    if (s_.compare(pos_, 9, "<!DOCTYPE") == 0) skip_past(">");
    skip_space();
    XmlElement root = element();
    skip_space();
    if (pos_ != s_.size()) fail("content after the root element");
    return root;
  }

private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML error at offset " + std::to_string(pos_) + ": " + what);
  }
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  void skip_past(const std::string& end) {
    auto p = s_.find(end, pos_);
    if (p == std::string::npos) fail("unterminated " + end);
    pos_ = p + end.size();
  }
  void expect(char c) {
    if (pos_ >= s_.size() || s_[pos_] != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  std::string name() {
    std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) ||
                                s_[pos_] == '_' || s_[pos_] == ':' || s_[pos_] == '-'))
      ++pos_;
    if (start == pos_) fail("expected a name");
    return s_.substr(start, pos_ - start);
  }
  static std::string unescape(const std::string& v) {
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (v[i] != '&') {
        out += v[i];
        continue;
      }
      static const std::pair<const char*, char> entities[] = {
          {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
      bool known = false;
      for (const auto& [entity, ch] : entities)
        if (v.compare(i, std::strlen(entity), entity) == 0) {
          out += ch, i += std::strlen(entity) - 1, known = true;
          break;
        }
      if (!known) throw std::runtime_error("XML error: unknown entity in " + v);
    }
    return out;
  }
  XmlElement element() {
    expect('<');
    XmlElement e;
    e.name = name();
    for (;;) {
      skip_space();
      if (pos_ < s_.size() && (s_[pos_] == '/' || s_[pos_] == '>')) break;
      std::string key = name();
      skip_space();
      expect('=');
      skip_space();
      expect('"');
      auto end = s_.find('"', pos_);
      if (end == std::string::npos) fail("unterminated attribute value");
      std::string value = s_.substr(pos_, end - pos_);
      if (value.find('<') != std::string::npos) fail("'<' in an attribute value");
      if (!e.attributes.emplace(key, unescape(value)).second) fail("attribute given twice");
      pos_ = end + 1;
    }
    if (s_[pos_] == '/') {
      ++pos_;
      expect('>');
      return e;
    }
    expect('>');
    for (;;) {
      auto lt = s_.find('<', pos_);
      if (lt == std::string::npos) fail("unterminated element " + e.name);
      e.text += unescape(s_.substr(pos_, lt - pos_));
      pos_ = lt;
      if (s_.compare(pos_, 2, "</") == 0) {
        pos_ += 2;
        if (name() != e.name) fail("mismatched end tag for " + e.name);
        skip_space();
        expect('>');
        return e;
      }
      e.children.push_back(element());
    }
  }
  std::string s_;
  std::size_t pos_ = 0;
};

std::vector<hsize_t> split_dims(const std::string& s) {
  std::istringstream in(s);
  std::vector<hsize_t> out;
  for (hsize_t v; in >> v;) out.push_back(v);
  return out;
}

// The shape of dataset `path` in HDF5 file `file`, or empty if there is none.
std::vector<hsize_t> dataset_shape(const fs::path& file, const std::string& path) {
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return {};
  std::vector<hsize_t> dims;
  H5E_auto2_t func;
  void* data;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  H5Eset_auto2(H5E_DEFAULT, func, data);
  if (d >= 0) {
    hid_t space = H5Dget_space(d);
    dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    H5Sclose(space);
    H5Dclose(d);
  }
  H5Fclose(f);
  return dims;
}

class FieldFileTest : public ScratchDirTest {
protected:
  FieldFileTest() : ScratchDirTest("twinflow_field_file_test") {}

  // Writes `count` snapshots; checks that after each append the file on disk holds all so far.
  FieldFile write_sequence(const Grid& grid, int count, const std::string& name = "fields") {
    FieldFile file(dir_ / name, grid);
    for (int i = 0; i < count; ++i) {
      file.append(make_snapshot(grid, i));
      EXPECT_EQ(FieldFile::read(file.h5_path()).snapshots.size(), static_cast<std::size_t>(i + 1));
      EXPECT_FALSE(fs::exists(dir_ / (name + ".h5.tmp")));
      EXPECT_FALSE(fs::exists(dir_ / (name + ".xdmf.tmp")));
    }
    return file;
  }
};

} // namespace

TEST_F(FieldFileTest, RoundTripIn1D2D3D) {
  for (int dim = 1; dim <= 3; ++dim) {
    SCOPED_TRACE("dim " + std::to_string(dim));
    const Grid grid = make_grid(dim);
    FieldFile file = write_sequence(grid, 3, "fields" + std::to_string(dim));
    const FieldFile::Contents c = FieldFile::read(file.h5_path());
    EXPECT_TRUE(c.grid == grid);
    ASSERT_EQ(c.snapshots.size(), 3u);
    for (int i = 0; i < 3; ++i) expect_same(c.snapshots[i], make_snapshot(grid, i));
    ASSERT_NE(c.snapshots[2].find("velocity"), nullptr);
    EXPECT_EQ(c.snapshots[2].find("velocity")->components, dim);
    EXPECT_EQ(c.snapshots[2].find("pressure"), nullptr);
  }
}

// Cell (i, j, k) with x fastest lands at dataset index [k][j][i]: the documented order.
TEST_F(FieldFileTest, CellOrderIsXFastest) {
  const Grid grid = make_grid(3);
  FieldFile file(dir_ / "order", grid);
  Snapshot s;
  s.time = 1;
  std::vector<double> v(static_cast<std::size_t>(grid.cell_count() * 3));
  for (std::size_t b = 0; b < v.size() / 3; ++b)
    for (int c = 0; c < 3; ++c) v[b * 3 + c] = static_cast<double>(b) + 0.1 * c;
  s.fields.push_back({"velocity", 3, v, {}});
  file.append(s);

  hid_t f = H5Fopen(file.h5_path().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t d = H5Dopen2(f, "/snapshots/000000/velocity", H5P_DEFAULT);
  ASSERT_GE(d, 0);
  std::vector<double> stored(v.size());
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, stored.data());
  H5Dclose(d);
  H5Fclose(f);
  const hsize_t nx = 5, ny = 4;
  const hsize_t i = 3, j = 2, k = 1; // flat cell index i + nx (j + ny k)
  EXPECT_EQ(stored[((k * ny + j) * nx + i) * 3 + 2],
            static_cast<double>(i + nx * (j + ny * k)) + 0.2);
  EXPECT_EQ(dataset_shape(file.h5_path(), "/snapshots/000000/velocity"),
            (std::vector<hsize_t>{3, 4, 5, 3}));
}

TEST_F(FieldFileTest, XdmfIsWellFormedAndReferencesExistingDatasetsOfItsShapes) {
  for (int dim = 1; dim <= 3; ++dim) {
    SCOPED_TRACE("dim " + std::to_string(dim));
    const Grid grid = make_grid(dim);
    FieldFile file = write_sequence(grid, 2, "fields" + std::to_string(dim));
    XmlElement root = XmlParser(twinflow::io::read_file(file.xdmf_path())).document();
    ASSERT_EQ(root.name, "Xdmf");
    ASSERT_EQ(root.all("Domain").size(), 1u);
    auto collections = root.all("Domain")[0]->all("Grid");
    ASSERT_EQ(collections.size(), 1u);
    EXPECT_EQ(collections[0]->attributes.at("GridType"), "Collection");
    EXPECT_EQ(collections[0]->attributes.at("CollectionType"), "Temporal");
    auto grids = collections[0]->all("Grid");
    ASSERT_EQ(grids.size(), 2u);

    const std::vector<hsize_t> nodes = {static_cast<hsize_t>(grid.counts[2] + 1),
                                        static_cast<hsize_t>(grid.counts[1] + 1),
                                        static_cast<hsize_t>(grid.counts[0] + 1)};
    for (std::size_t i = 0; i < grids.size(); ++i) {
      const XmlElement& g = *grids[i];
      const Snapshot expected = make_snapshot(grid, static_cast<int>(i));
      ASSERT_EQ(g.all("Time").size(), 1u);
      EXPECT_EQ(std::stod(g.all("Time")[0]->attributes.at("Value")), expected.time);
      ASSERT_EQ(g.all("Topology").size(), 1u);
      EXPECT_EQ(g.all("Topology")[0]->attributes.at("TopologyType"), "3DCoRectMesh");
      EXPECT_EQ(split_dims(g.all("Topology")[0]->attributes.at("Dimensions")), nodes);
      ASSERT_EQ(g.all("Geometry").size(), 1u);
      auto geometry = g.all("Geometry")[0]->all("DataItem");
      ASSERT_EQ(geometry.size(), 2u);
      std::istringstream origin(geometry[0]->text), spacing(geometry[1]->text);
      double oz, oy, ox, dz, dy, dx;
      origin >> oz >> oy >> ox;
      spacing >> dz >> dy >> dx;
      EXPECT_EQ(ox, grid.origin[0]);
      EXPECT_EQ(dx, grid.spacing[0]);
      if (dim >= 2) {
        EXPECT_EQ(dy, grid.spacing[1]);
      }
      if (dim == 3) {
        EXPECT_EQ(oz, grid.origin[2]);
      }

      // Every field and its standard error appear, each pointing at a dataset of its shape.
      std::size_t expected_attributes = 0;
      for (const Field& f : expected.fields)
        expected_attributes += f.standard_error.empty() ? 1 : 2;
      auto attributes = g.all("Attribute");
      EXPECT_EQ(attributes.size(), expected_attributes);
      for (const XmlElement* a : attributes) {
        const std::string name = a->attributes.at("Name");
        SCOPED_TRACE(name);
        EXPECT_EQ(a->attributes.at("Center"), "Cell");
        const bool vector = name.rfind("velocity", 0) == 0 && dim > 1;
        EXPECT_EQ(a->attributes.at("AttributeType"), vector ? "Vector" : "Scalar");
        ASSERT_EQ(a->all("DataItem").size(), 1u);
        const XmlElement& item = *a->all("DataItem")[0];
        EXPECT_EQ(item.attributes.at("Format"), "HDF");
        const std::string ref = item.text;
        const auto colon = ref.find(':');
        ASSERT_NE(colon, std::string::npos) << ref;
        const fs::path h5 = file.xdmf_path().parent_path() / ref.substr(0, colon);
        EXPECT_EQ(h5, file.h5_path());
        const std::vector<hsize_t> declared = split_dims(item.attributes.at("Dimensions"));
        EXPECT_EQ(dataset_shape(h5, ref.substr(colon + 1)), declared) << ref;
        std::vector<hsize_t> cells(nodes);
        for (hsize_t& n : cells) --n;
        if (vector) cells.push_back(static_cast<hsize_t>(dim));
        EXPECT_EQ(declared, cells);
      }
    }
  }
}

TEST_F(FieldFileTest, XmllintAcceptsTheXdmf) {
  if (std::system("xmllint --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no xmllint";
  FieldFile file = write_sequence(make_grid(2), 2);
  const std::string command = "xmllint --noout '" + file.xdmf_path().string() + "'";
  EXPECT_EQ(std::system(command.c_str()), 0);
}

TEST_F(FieldFileTest, H5pyReadsTheFile) {
  // Debian's h5py is for /usr/bin/python3; a python3 earlier in PATH (pyenv) may lack it.
  std::string python;
  for (const char* candidate : {"python3", "/usr/bin/python3"}) {
    const std::string probe = std::string(candidate) + " -c 'import h5py' > /dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) {
      python = candidate;
      break;
    }
  }
  if (python.empty()) GTEST_SKIP() << "no python3 with h5py";
  const Grid grid = make_grid(2);
  FieldFile file = write_sequence(grid, 2);
  const fs::path script = dir_ / "check.py";
  std::ofstream(script) << "import sys, h5py\n"
                           "f = h5py.File(sys.argv[1], 'r')\n"
                           "assert f.attrs['format'] in (b'twinflow-fields', 'twinflow-fields')\n"
                           "assert int(f.attrs['format_version']) == 1\n"
                           "assert int(f['grid'].attrs['dim']) == 2\n"
                           "assert list(f['grid'].attrs['counts']) == [5, 4]\n"
                           "assert list(f['times'][:]) == [10.0, 20.0]\n"
                           "s = f['snapshots/000001']\n"
                           "assert s.attrs['particle_steps'] == 2000\n"
                           "assert s['velocity'].shape == (1, 4, 5, 2)\n"
                           "assert s['velocity_stderr'].shape == (1, 4, 5, 2)\n"
                           "assert s['density'].shape == (1, 4, 5)\n"
                           "assert abs(s['velocity'][0, 1, 2, 1] - (105 + 0.001 * 15)) < 1e-12\n"
                           "assert 'cell_volume_stderr' not in s\n"
                           "print('ok')\n";
  const std::string command =
      python + " '" + script.string() + "' '" + file.h5_path().string() + "'";
  EXPECT_EQ(std::system(command.c_str()), 0);
}

// The openmpi HDF5 (the one deal.II links) with the default driver in a process without MPI.
TEST_F(FieldFileTest, ParallelHdf5WorksWithoutMpiInit) {
#ifdef H5_HAVE_PARALLEL
  FieldFile file = write_sequence(make_grid(3), 2);
  EXPECT_EQ(FieldFile::read(file.h5_path()).snapshots.size(), 2u);
  int initialized = 1;
  MPI_Initialized(&initialized);
  EXPECT_EQ(initialized, 0) << "something initialised MPI";
#else
  GTEST_SKIP() << "built against a serial HDF5; the top-level CMakeLists asks for the parallel one";
#endif
}

TEST_F(FieldFileTest, AppendRejectsBadSnapshotsAndKeepsTheFiles) {
  const Grid grid = make_grid(2);
  FieldFile file = write_sequence(grid, 1);
  const std::string xdmf_before = twinflow::io::read_file(file.xdmf_path());
  auto bad = [&](auto change) {
    Snapshot s = make_snapshot(grid, 1);
    change(s);
    EXPECT_THROW(file.append(s), std::invalid_argument);
  };
  bad([](Snapshot& s) { s.time = 10.0; }); // not after the first snapshot
  bad([](Snapshot& s) { s.time = std::numeric_limits<double>::quiet_NaN(); });
  bad([](Snapshot& s) { s.fields[0].values.pop_back(); });
  bad([](Snapshot& s) { s.fields[0].standard_error.pop_back(); });
  bad([](Snapshot& s) { s.fields[2].components = 3; });
  bad([](Snapshot& s) { s.fields[1].name = "density"; });
  bad([](Snapshot& s) { s.fields[1].name = "temperature/kinetic"; });
  bad([](Snapshot& s) { s.fields[1].name = "density_stderr"; });
  bad([](Snapshot& s) { s.fields[1].name = ""; });
  EXPECT_EQ(file.snapshots().size(), 1u);
  EXPECT_EQ(FieldFile::read(file.h5_path()).snapshots.size(), 1u);
  EXPECT_EQ(twinflow::io::read_file(file.xdmf_path()), xdmf_before);
  file.append(make_snapshot(grid, 1)); // still usable
  EXPECT_EQ(FieldFile::read(file.h5_path()).snapshots.size(), 2u);
}

TEST_F(FieldFileTest, GridIsValidated) {
  Grid g = make_grid(2);
  g.dim = 4;
  EXPECT_THROW(FieldFile(dir_ / "a", g), std::invalid_argument);
  g = make_grid(2);
  g.counts[2] = 2; // an axis the grid does not have
  EXPECT_THROW(FieldFile(dir_ / "a", g), std::invalid_argument);
  g = make_grid(3);
  g.spacing[1] = 0;
  EXPECT_THROW(FieldFile(dir_ / "a", g), std::invalid_argument);
  g = make_grid(3);
  g.counts[0] = 0;
  EXPECT_THROW(FieldFile(dir_ / "a", g), std::invalid_argument);
}

// A new run must not leave an earlier run's complete-looking files, nor trip over its .tmp.
TEST_F(FieldFileTest, NewSequenceRemovesEarlierFilesAndIgnoresStaleTmp) {
  const Grid grid = make_grid(3);
  write_sequence(grid, 2);
  twinflow::io::write_file_atomically(dir_ / "fields.h5.tmp.keep", "x"); // unrelated: untouched
  std::ofstream(dir_ / "fields.h5.tmp") << "half-written HDF5 from a killed run";
  FieldFile again(dir_ / "fields", grid);
  EXPECT_FALSE(fs::exists(again.h5_path()));
  EXPECT_FALSE(fs::exists(again.xdmf_path()));
  again.append(make_snapshot(grid, 0));
  EXPECT_EQ(FieldFile::read(again.h5_path()).snapshots.size(), 1u);
  EXPECT_FALSE(fs::exists(dir_ / "fields.h5.tmp"));
  EXPECT_TRUE(fs::exists(dir_ / "fields.h5.tmp.keep"));
}

TEST_F(FieldFileTest, ReadRejectsMissingTruncatedAndForeignFiles) {
  const fs::path missing = dir_ / "missing.h5";
  EXPECT_NE(input_error_of([&] { FieldFile::read(missing); }).find(missing.string()),
            std::string::npos);

  FieldFile file = write_sequence(make_grid(3), 2);
  const std::string bytes = twinflow::io::read_file(file.h5_path());
  const fs::path cut = dir_ / "cut.h5";
  twinflow::io::write_file_atomically(cut, bytes.substr(0, bytes.size() / 2));
  EXPECT_NE(input_error_of([&] { FieldFile::read(cut); }).find(cut.string()), std::string::npos);

  const fs::path foreign = dir_ / "foreign.h5"; // valid HDF5, not ours
  hid_t f = H5Fcreate(foreign.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  H5Fclose(f);
  const std::string message = input_error_of([&] { FieldFile::read(foreign); });
  EXPECT_NE(message.find(foreign.string()), std::string::npos) << message;
  EXPECT_NE(message.find("format"), std::string::npos) << message;

  const fs::path text = dir_ / "text.h5";
  twinflow::io::write_file_atomically(text, "not HDF5");
  EXPECT_NE(input_error_of([&] { FieldFile::read(text); }).find("not an HDF5 file"),
            std::string::npos);
}
