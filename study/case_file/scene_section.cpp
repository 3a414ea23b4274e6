#include "study/case_file/case_file.hpp"

namespace twinflow::study {

namespace {
const char* kAxes[3] = {"x", "y", "z"};
}

void declare_scene(Registry& r) {
  using namespace dealii::Patterns;
  r.declare("Scene/Dimension", "3", Integer(2, 3), "Space dimension of both twins.");
  r.declare("Scene/Box size", "20, 10, 10", List(Double(), 2, 3),
            "Box edge lengths Lx, Ly[, Lz] in units of rc; Lz is ignored in 2D.");
  r.declare_positive("Scene/Density", "3", "Number density rho (particles per volume), > 0.");
  r.declare_positive(
      "Scene/Temperature", "1",
      "Initial temperature T (units of T0), > 0; the fixed temperature of isothermal DPD.");
  r.declare("Scene/Temperature perturbation", "0", Double(0, 0.9),
            "Relative amplitude A of an initial temperature mode T (1 + A sin(2 pi x / Lx)) (the "
            "thermal relaxation scene; its decay gives chi and kappa); 0: uniform.",
            "0 <= A <= 0.9");
  r.declare("Scene/Shear perturbation", "0", Double(0, 2),
            "Amplitude U of an initial transverse velocity mode v_y = U sqrt(k T / m) "
            "sin(2 pi x / Lx), in units of the thermal speed (the relaxation scene; its decay "
            "gives nu and eta); 0: none. Needs 2D or 3D and a periodic x.",
            "0 <= U <= 2");
  r.declare("Scene/Reverse Poiseuille force", "0", Double(),
            "Body force F per particle along x, +F where y < Ly/2 and -F above (the reverse "
            "Poiseuille flow that measures the viscosity from the two parabolic halves; between "
            "walls along y, each half's parabola extrapolated to its wall also gives the wall's "
            "slip length); 0: none. Needs a periodic x. The work it does heats the fluid.");
  r.declare("Scene/Gravity", "0, 0, 0", List(Double(), 2, 3),
            "Gravitational acceleration vector g (force m g on every particle).");
  r.declare("Scene/Field bins", "10", List(Integer(1, 100000), 1, 3),
            "Regular grid of bins on which both twins' fields are averaged and compared: one "
            "count for all directions, or one per direction (1 = averaged over that direction).");
  const std::string h = "Scene/Heat slabs/";
  r.declare(h + "Direction", "x", Selection("x|y|z"), "Normal direction of the heat slabs.");
  r.declare(h + "Hot slab", "", List(Double(0), 0, 2),
            "lower, upper bound of the slab that receives +Power; empty: no slabs.");
  r.declare(h + "Cold slab", "", List(Double(0), 0, 2),
            "lower, upper bound of the slab that loses Power.");
  r.declare(h + "Power", "0", Double(0),
            "Heat per time put into the hot slab and taken from the cold one (k T0 / tau). In a "
            "periodic box the heat leaves the hot slab both ways: seed 002's mean flux J0 is "
            "Power / (2 A), A the slab's cross-section.");
  for (const char* axis : kAxes) {
    const std::string s = std::string("Scene/") + axis + " boundaries/";
    r.declare(s + "Type", "periodic", Selection("periodic|walls"),
              std::string("Periodic in ") + axis + ", or a wall at each end.");
    r.declare(s + "Lower wall", "thermal", Selection("thermal|adiabatic"),
              "Lower wall: thermal (fixed temperature, exchanges heat) or adiabatic.");
    r.declare(s + "Upper wall", "thermal", Selection("thermal|adiabatic"),
              "Upper wall: thermal or adiabatic.");
    r.declare_positive(s + "Lower wall temperature", "1",
                       "Temperature of a thermal lower wall, > 0.");
    r.declare_positive(s + "Upper wall temperature", "1",
                       "Temperature of a thermal upper wall, > 0.");
    r.declare(s + "Slip", "free-slip", Selection("free-slip|no-slip"),
              "Tangential condition at both walls of this direction.");
  }
}

scene::SceneParameters resolve_scene(const Registry& r) {
  scene::SceneParameters s;
  s.dim = static_cast<int>(r.get_integer("Scene/Dimension"));
  const auto box = r.get_doubles("Scene/Box size");
  r.require(static_cast<int>(box.size()) >= s.dim, "Scene/Box size",
            "one length per dimension (" + std::to_string(s.dim) + ")");
  for (int d = 0; d < 3; ++d) s.box[d] = d < static_cast<int>(box.size()) ? box[d] : 1.0;
  for (int d = 0; d < s.dim; ++d) r.require(s.box[d] > 0, "Scene/Box size", "lengths > 0");
  s.density = r.get_positive("Scene/Density");
  s.temperature = r.get_positive("Scene/Temperature");
  s.temperature_perturbation = r.get_double("Scene/Temperature perturbation");
  s.shear_perturbation = r.get_double("Scene/Shear perturbation");
  s.poiseuille_force = r.get_double("Scene/Reverse Poiseuille force");
  const auto g = r.get_doubles("Scene/Gravity");
  for (std::size_t d = 0; d < g.size(); ++d) s.gravity[d] = g[d];
  for (int d = 0; d < 3; ++d) {
    const std::string p = std::string("Scene/") + kAxes[d] + " boundaries/";
    auto& b = s.boundary[d];
    b.periodic = r.get(p + "Type") == "periodic" || d >= s.dim;
    b.thermal = {{r.get(p + "Lower wall") == "thermal", r.get(p + "Upper wall") == "thermal"}};
    b.temperature = {
        {r.get_double(p + "Lower wall temperature"), r.get_double(p + "Upper wall temperature")}};
    b.no_slip = r.get(p + "Slip") == "no-slip";
    if (!b.periodic) {
      for (int side = 0; side < 2; ++side) {
        const std::string key = p + (side ? "Upper" : "Lower") + " wall temperature";
        r.require(!b.thermal[side] || b.temperature[side] > 0, key, Registry::kPositive);
      }
    }
  }
  const std::string h = "Scene/Heat slabs/";
  const auto hot = r.get_doubles(h + "Hot slab"), cold = r.get_doubles(h + "Cold slab");
  const double power = r.get_double(h + "Power");
  const int direction = static_cast<int>(std::string("xyz").find(r.get(h + "Direction")));
  if (power > 0 || !hot.empty() || !cold.empty()) {
    r.require(direction < s.dim, h + "Direction", "a direction of the scene's dimension");
    for (const bool is_hot : {true, false}) {
      const auto& slab = is_hot ? hot : cold;
      r.require(slab.size() == 2 && slab[0] < slab[1] && slab[1] <= s.box[direction],
                h + (is_hot ? "Hot slab" : "Cold slab"),
                "lower, upper with 0 <= lower < upper <= box length");
      s.heat_slabs.push_back({direction, slab[0], slab[1], is_hot ? power : -power});
    }
  }
  const auto bins = r.get_doubles("Scene/Field bins");
  r.require(bins.size() == 1 || static_cast<int>(bins.size()) == s.dim, "Scene/Field bins",
            "one value, or one per dimension");
  for (int d = 0; d < s.dim; ++d)
    s.bins[d] = static_cast<int>(bins.size() == 1 ? bins[0] : bins[d]);
  return s;
}

} // namespace twinflow::study
