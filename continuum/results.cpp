#include "continuum/results.hpp"

#include <iomanip>
#include <sstream>

namespace twinflow::continuum {

namespace {
io::Json triple(const std::array<double, 3>& a, int dim) {
  return io::Json(std::vector<double>(a.begin(), a.begin() + dim));
}
io::Json cells_json(const std::array<unsigned, 3>& a, int dim) {
  io::Json j = io::Json::array();
  for (int d = 0; d < dim; ++d) j.push_back(a[d]);
  return j;
}
io::Json power_law(const PowerLaw& law) {
  io::Json j = io::Json::object();
  j["value_at_reference"] = law.value_at_reference;
  j["exponent"] = law.exponent;
  if (law.sutherland_temperature > 0) j["sutherland_temperature"] = law.sutherland_temperature;
  if (law.pair_fraction > 0) {
    j["pair_fraction"] = law.pair_fraction;
    j["pair_exponent"] = law.pair_exponent;
  }
  return j;
}
// Per direction: periodic, or the two walls (temperature or flux, Kapitza, slip).
io::Json boundaries_json(const ContinuumParameters& p) {
  io::Json walls = io::Json::array();
  for (int d = 0; d < p.dim; ++d) {
    const auto& b = p.boundary[d];
    io::Json w = io::Json::object();
    w["direction"] = std::string(1, "xyz"[d]);
    w["periodic"] = b.periodic;
    if (!b.periodic) {
      for (int side = 0; side < 2; ++side) {
        io::Json s = io::Json::object();
        s["fixed_temperature"] = b.fixed_temperature[side];
        if (b.fixed_temperature[side]) s["temperature"] = b.temperature[side];
        if (b.robin(side)) {
          s["kapitza_conductance"] = b.kapitza_conductance[side];
          s["kapitza_conductance_stderr"] = b.kapitza_conductance_stderr[side];
        } else if (!b.fixed_temperature[side])
          s["heat_flux_in"] = b.heat_flux[side];
        if (b.pinned_depth[side] > 0) s["pinned_depth"] = b.pinned_depth[side];
        if (b.kinetic_slip[side])
          s["slip"] = "kinetic";
        else if (b.navier(side))
          s["slip_length"] = b.slip_length[side];
        w[side ? "upper" : "lower"] = s;
      }
      w["velocity"] = b.no_slip ? "no-slip" : "free-slip";
    }
    walls.push_back(w);
  }
  return walls;
}
io::Json heat_slabs_json(const std::vector<HeatSlab>& heat_slabs) {
  io::Json slabs = io::Json::array();
  for (const auto& s : heat_slabs) {
    io::Json o = io::Json::object();
    o["direction"] = s.direction;
    o["lower"] = s.lower;
    o["upper"] = s.upper;
    o["power"] = s.power;
    slabs.push_back(o);
  }
  return slabs;
}
} // namespace

namespace {
const char* model_name(Model model) {
  return model == Model::Boussinesq     ? "boussinesq"
         : model == Model::LowMach      ? "low-mach"
         : model == Model::Compressible ? "compressible"
                                        : "heat-conduction";
}

io::Json equation_of_state_json(const ContinuumParameters& p) {
  io::Json eos = io::Json::object();
  eos["form"] = "p = n k T + n^2 (b0 + b1 k T + b2 (n - n_ref))";
  eos["b0"] = p.equation_of_state.b0;
  eos["b1"] = p.equation_of_state.b1;
  eos["b2"] = p.equation_of_state.b2;
  eos["n_ref"] = p.equation_of_state.n_ref;
  return eos;
}

io::Json wall_friction_json(const ContinuumParameters& p) {
  return {{"form", "beta = 2 n [sqrt(m k T / 2 pi) + rho_w I_d gamma(T, T_w)], "
                   "gamma = gamma_constant + gamma_inverse (1/T + 1/T_w)"},
          {"wall_density", p.wall_friction.wall_density},
          {"tangent_moment", p.wall_friction.tangent_moment},
          {"gamma_constant", p.wall_friction.gamma_constant},
          {"gamma_inverse", p.wall_friction.gamma_inverse}};
}

// A transient twin's time keys into j.
void add_time_stepping(io::Json& j, const ContinuumParameters& p) {
  j["end_time"] = p.end_time;
  j["time_step"] = p.time_step;
  if (p.model == Model::HeatConduction)
    j["theta"] = p.theta;
  else
    j["time_scheme"] = p.model == Model::LowMach ? "implicit Euler" : "BDF2 (first step BDF1)";
  j["initial_temperature"] = p.initial_temperature;
  j["snapshot_times"] = p.snapshot_times;
  j["snapshot_every"] = p.snapshot_every;
  j["series_every"] = p.series_every;
}
} // namespace

io::Json to_json(const ContinuumParameters& p) {
  io::Json j = io::Json::object();
  j["model"] = model_name(p.model);
  j["dim"] = p.dim;
  j["box"] = triple(p.box, p.dim);
  if (p.bin_box[0] > 0) { // the scene's box in this twin's coordinates (walls moved in)
    j["scene_lower"] = triple(p.bin_lower, p.dim);
    j["scene_box"] = triple(p.bin_box, p.dim);
  }
  j["boundaries"] = boundaries_json(p);
  j["gravity"] = triple(p.gravity, p.dim);
  j["number_density"] = p.number_density;
  if (p.particle_count > 0) j["particle_count"] = p.particle_count;
  j["particle_mass"] = p.particle_mass;
  j["heat_capacity_per_particle"] = p.heat_capacity;
  j["thermal_expansion"] = p.thermal_expansion;
  j["reference_temperature"] = p.reference_temperature;
  j["viscosity"] = power_law(p.viscosity);
  if (p.model == Model::LowMach || p.model == Model::Compressible)
    j["equation_of_state"] = equation_of_state_json(p);
  if (p.model == Model::Compressible) j["bulk_viscosity"] = p.bulk_viscosity;
  j["conductivity"] = power_law(p.conductivity);
  bool kinetic = false;
  for (const auto& b : p.boundary) kinetic = kinetic || b.kinetic_slip[0] || b.kinetic_slip[1];
  if (kinetic) j["wall_friction"] = wall_friction_json(p);
  j["heat_slabs"] = heat_slabs_json(p.heat_slabs);
  j["coarse_cells"] = cells_json(p.cells, p.dim);
  j["refinements"] = p.refinements;
  j["newton_tolerance"] = p.newton_tolerance;
  j["continuation_start_rayleigh"] = p.continuation_start_rayleigh;
  j["mode"] = p.transient() ? "transient" : "steady";
  if (p.transient()) add_time_stepping(j, p);
  j["bins"] = cells_json(p.bins, p.dim);
  return j;
}

namespace {
io::Json numbers_json(const DimensionlessNumbers& n) {
  io::Json numbers = io::Json::object();
  numbers["kinematic_viscosity_nu"] = n.kinematic_viscosity;
  numbers["thermal_diffusivity_chi"] = n.thermal_diffusivity;
  numbers["rayleigh"] = n.rayleigh;
  numbers["prandtl"] = n.prandtl;
  numbers["heated_direction"] = n.heated_direction;
  numbers["height_H"] = n.height;
  numbers["temperature_difference"] = n.temperature_difference;
  numbers["velocity_scale_chi_over_H"] = n.velocity_scale;
  numbers["conduction_flux"] = n.conduction_flux;
  numbers["epsilon"] = n.epsilon;
  return numbers;
}

// What the low-Mach and compressible models add: the mass and the pressure.
void variable_density_results(const ContinuumResult& r, io::Json& results) {
  if (r.model == "compressible") {
    results["relative_mass_error"] = r.mass_error;
    results["mean_pressure_over_p0"] = r.pressure_ratio; // p0 = n0 k T_ref
    results["number_density_min"] = r.density_min;
    results["number_density_max"] = r.density_max;
  }
  if (r.model == "low-mach") {
    results["thermodynamic_pressure"] = r.thermodynamic_pressure;
    results["pressure_ratio_P_over_p0"] = r.pressure_ratio;
    results["relative_mass_error"] = r.mass_error;
    results["number_density_min"] = r.density_min;
    results["number_density_max"] = r.density_max;
    results["wall_nusselt_consistent_flux"] = r.consistent_wall_nusselt;
    if (r.time_steps > 0) {
      results["time"] = r.time;
      results["time_steps"] = r.time_steps;
    }
  }
}

// The roll: wall Nu, mid-line maxima (de Vahl Davis's numbers), the stream function's maximum.
void roll_results(const ContinuumResult& r, io::Json& results) {
  io::Json walls = io::Json::array();
  for (const auto& w : r.walls) {
    io::Json o = io::Json::object();
    o["wall"] = std::string(1, "xyz"[w.direction]) + (w.side ? " upper" : " lower");
    o["nusselt_average"] = w.average;
    walls.push_back(o);
  }
  results["wall_nusselt"] = walls;
  if (r.has_midline_maxima) {
    io::Json u = io::Json::object();
    u["value_chi_over_H"] = r.u_max_vertical_midline.value;
    u["y_over_Ly"] = r.u_max_vertical_midline.position;
    results["u_max_on_x_mid"] = u;
    io::Json v = io::Json::object();
    v["value_chi_over_H"] = r.v_max_horizontal_midline.value;
    v["x_over_Lx"] = r.v_max_horizontal_midline.position;
    results["v_max_on_y_mid"] = v;
  }
  if (r.stream_function_max > 0) {
    results["stream_function_max_over_chi"] = r.stream_function_max;
    results["vortex_centre_fraction_of_box"] =
        std::vector<double>{r.vortex_centre[0], r.vortex_centre[1]};
  }
  results["max_speed_chi_over_H"] = r.max_speed;
  results["kinetic_energy"] = r.kinetic_energy;
  results["newton_iterations"] = r.newton_iterations;
}

io::Json time_series_json(const ContinuumResult& r) {
  io::Json series = io::Json::object();
  std::vector<double> t, nu, ke, speed;
  for (const auto& s : r.time_series) {
    t.push_back(s.time);
    nu.push_back(s.nusselt);
    ke.push_back(s.kinetic_energy);
    speed.push_back(s.max_speed);
  }
  series["time"] = t;
  series["nusselt"] = nu;
  series["kinetic_energy"] = ke;
  series["max_speed_chi_over_H"] = speed;
  return series;
}

io::Json mesh_study_json(const ContinuumResult& r) {
  io::Json study = io::Json::array();
  for (const auto& m : r.mesh_study) {
    io::Json o = io::Json::object();
    o["level"] = m.level;
    o["cells"] = cells_json(m.cells, r.dim);
    o["dofs"] = m.dofs;
    o["nusselt"] = m.nusselt;
    o["change_in_nusselt"] = m.change_in_nusselt;
    if (m.pressure_ratio > 0) o["pressure_ratio"] = m.pressure_ratio;
    o["newton_iterations"] = m.newton_iterations;
    o["wall_time_s"] = m.wall_time;
    study.push_back(o);
  }
  return study;
}

// A flow model's results (Boussinesq, low-Mach, compressible).
io::Json flow_results(const ContinuumResult& r) {
  io::Json results = io::Json::object();
  results["nusselt_volume_average"] = r.nusselt;
  variable_density_results(r, results);
  roll_results(r, results);
  if (!r.time_series.empty()) {
    results["time"] = r.time;
    results["time_steps"] = r.time_steps;
    results["time_step"] = r.time_step;
    results["time_series"] = time_series_json(r);
  }
  results["continuation_rayleigh"] = r.continuation_rayleigh;
  results["mesh_study"] = mesh_study_json(r);
  return results;
}

io::Json probes_json(const ContinuumResult& r) {
  io::Json probes = io::Json::array();
  for (std::size_t i = 0; i < r.probe_points.size(); ++i) {
    io::Json o = io::Json::object();
    o["point"] = triple(r.probe_points[i], r.dim);
    io::Json values = io::Json::object();
    // the FE components only (the bins' derived fields come after them)
    for (std::size_t c = 0; c < std::min(r.bins.names.size(), r.probe_values[i].size()); ++c)
      values[r.bins.names[c]] = r.probe_values[i][c];
    o["values"] = values;
    probes.push_back(o);
  }
  return probes;
}
} // namespace

io::Json to_json(const ContinuumResult& r) {
  io::Json j = io::Json::object();
  j["dimensionless"] = numbers_json(r.numbers);
  io::Json mesh = io::Json::object();
  mesh["cells"] = cells_json(r.cells, r.dim);
  mesh["dofs"] = r.dofs;
  j["mesh"] = mesh;
  io::Json results = io::Json::object();
  if (r.model == "boussinesq" || r.model == "low-mach" || r.model == "compressible") {
    results = flow_results(r);
  } else {
    results["time"] = r.time;
    results["time_steps"] = r.time_steps;
    results["newton_iterations"] = r.newton_iterations;
    results["heat_into_lower_wall_face"] = r.heat_flux_lower;
    results["heat_into_upper_wall_face"] = r.heat_flux_upper;
  }
  results["temperature_min"] = r.temperature_min;
  results["temperature_max"] = r.temperature_max;
  results["temperature_mean"] = r.temperature_mean;
  results["probes"] = probes_json(r);
  j["results"] = results;
  io::Json times = io::Json::object();
  times["setup"] = r.times.setup;
  times["assembly"] = r.times.assembly;
  times["solve"] = r.times.solve;
  times["postprocess"] = r.times.postprocess;
  times["output"] = r.times.output;
  times["total"] = r.times.total();
  j["wall_time_s"] = times;
  j["files"] = io::Json::array();
  for (const auto& f : r.files) j["files"].push_back(f);
  return j;
}

namespace {
void bins_header(std::ostream& out, const BinAverages& bins, int dim) {
  const char* axes = "xyz";
  for (int d = 0; d < dim; ++d) out << "i" << axes[d] << ",";
  for (int d = 0; d < dim; ++d) out << axes[d] << "_centre,";
  for (std::size_t c = 0; c < bins.names.size(); ++c)
    out << bins.names[c] << (c + 1 < bins.names.size() ? "," : "\n");
}

// Each bin's line after `prefix`: indices (x fastest), centre, every field.
void bins_rows(std::ostream& out, const BinAverages& bins, const ContinuumParameters& p, int dim,
               const std::string& prefix) {
  const auto& b = bins.bins;
  const unsigned n = b[0] * (dim > 1 ? b[1] : 1) * (dim > 2 ? b[2] : 1);
  for (unsigned k = 0; k < n; ++k) {
    unsigned rest = k;
    std::array<unsigned, 3> idx{{0, 0, 0}};
    for (int d = 0; d < dim; ++d) idx[d] = rest % b[d], rest /= b[d];
    out << prefix;
    for (int d = 0; d < dim; ++d) out << idx[d] << ",";
    for (int d = 0; d < dim; ++d) out << (idx[d] + 0.5) * p.bin_extent(d) / b[d] << ",";
    for (std::size_t c = 0; c < bins.names.size(); ++c)
      out << bins.values[c][k] << (c + 1 < bins.names.size() ? "," : "\n");
  }
}
} // namespace

std::string bins_csv(const ContinuumResult& r, const ContinuumParameters& p) {
  std::ostringstream out;
  out << std::setprecision(12);
  bins_header(out, r.bins, r.dim);
  bins_rows(out, r.bins, p, r.dim, "");
  return out.str();
}

std::string bin_responses_csv(const std::vector<BinResponse>& responses,
                              const ContinuumParameters& p, int dim) {
  std::ostringstream out;
  out << std::setprecision(12)
      << "# the twin's bins with one input moved by +1 standard error, minus its own\n";
  if (responses.empty()) return out.str();
  out << "input,";
  bins_header(out, responses.front().change, dim);
  for (const BinResponse& r : responses) bins_rows(out, r.change, p, dim, r.input + ",");
  return out.str();
}

std::string time_series_csv(const ContinuumResult& r) {
  std::ostringstream out;
  out << std::setprecision(12)
      << "# Boussinesq in time, BDF2 (first step BDF1); nusselt: volume form; kinetic_energy: int "
         "(1/2) n m |u|^2 dV (particle units); max_speed: units chi/H\n"
      << "step,time,nusselt,kinetic_energy,max_speed,newton_iterations\n";
  for (const auto& s : r.time_series)
    out << s.step << "," << s.time << "," << s.nusselt << "," << s.kinetic_energy << ","
        << s.max_speed << "," << s.newton_iterations << "\n";
  return out.str();
}

std::string wall_nusselt_csv(const ContinuumResult& r) {
  std::ostringstream out;
  out << std::setprecision(12) << "wall,x,y,z,nusselt_local\n";
  for (const auto& w : r.walls)
    for (std::size_t i = 0; i < w.local.size(); ++i)
      out << "xyz"[w.direction] << (w.side ? "_upper," : "_lower,") << w.points[i][0] << ","
          << w.points[i][1] << "," << w.points[i][2] << "," << w.local[i] << "\n";
  return out.str();
}

} // namespace twinflow::continuum
