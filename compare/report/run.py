"""The report of a run directory (DIR/compare/metrics.json): the twins' distances, heat flows,
wall jumps and calibration, the continuum twins' own errors, and the figures fields.png,
density.png (low-Mach twin), profiles.png, wall_layers.png and error_vs_time.png."""

import math
import os

from .data import (TWIN_LABEL, TWINS, UNITS_NOTE, finite, fmt, fmt_percent, fmt_pm,
                   lookup, number, read_json, read_table, to_float)
from .document import Document, write_documents
from .run_figures import RunGeometry, figure_error_vs_time, figure_fields, figure_profiles, \
    figure_wall_layers, wall_layer_table

# A difference counts as "within noise" when it exceeds the noise by at most this many standard
# errors (stated in every report that uses it).
WITHIN_NOISE_STDERRS = 2.0


def calibration_text(metrics):
    """How the calibrated twin's walls were set (compare/metrics.json), for captions (only
    asked when there is a calibrated twin)."""
    return lookup(metrics, "twins", "calibrated", "calibration") or \
        "walls at the fluid's wall temperatures"


def heat_flow_optional(particle):
    """Whether the Nusselt keys may be absent: the compare stage writes them only for a scene
    with a heated direction (metrics.json particle.nusselt is there)."""
    return lookup(particle, "nusselt", optional=True) is None


def within_noise_sentence(name, distance):
    l2, se, noise = (number(distance, k) for k in ("l2", "l2_stderr", "noise"))
    if not (finite(l2) and finite(noise)):
        return f"{name}: no L2 in metrics.json."
    # The twin's own error from its measured inputs, where compare had their responses.
    twin = number(distance, "noise_twin", optional=True)
    twin = twin if finite(twin) and twin > 0 else 0.0
    errors = math.hypot(noise, twin)
    head = f"{name}: L2 = {fmt_pm(l2, se)} against a noise of {fmt(noise, 3)}"
    if twin > 0:
        head += (f" and the twin's {fmt(twin, 3)} from its measured inputs' errors "
                 f"({fmt(errors, 3)} together)")
    within, beyond = ("within errors", "not within errors: a difference between the twins") \
        if twin > 0 else ("within noise", "not within noise: a difference between the twins")
    if finite(se) and se > 0:
        over = (l2 - errors) / se
        verdict = within if over <= WITHIN_NOISE_STDERRS else beyond
        side = "above" if over >= 0 else "below"
        return f"{head}, {fmt(abs(over), 3)} standard errors {side} it — {verdict}."
    return head + (f" — {within}." if l2 <= errors else
                   " — above the noise (no standard error).")


def nusselt_sentence(twin, twin_metrics, particle, optional=False):
    """optional: the scene may have no heated direction (then no Nusselt keys)."""
    difference = number(twin_metrics, "nusselt_particle_minus_twin", optional=optional)
    se = number(particle, "nusselt_stderr", optional=optional)
    twin_se = number(twin_metrics, "nusselt_stderr_from_coefficients", optional=optional)
    if not finite(difference):
        return None
    text = (f"Nusselt number, {TWIN_LABEL[twin]}: particle − twin = {fmt(difference)}"
            f" ({fmt_percent(number(twin_metrics, 'nusselt_relative_difference'))} of the twin's)")
    if finite(twin_se) and finite(se):
        # The twin's error: its heat flux's response to the measured coefficients' errors (and
        # the Kapitza twin's to its conductances').
        both = math.hypot(se, twin_se)
        over = abs(difference) / both
        verdict = "within the errors" if over <= WITHIN_NOISE_STDERRS else "not within the errors"
        return text + (f", {fmt(over, 3)} combined standard errors (particle {fmt(se, 2)}, twin "
                       f"{fmt(twin_se, 2)} from its measured inputs) — {verdict}.")
    if finite(se) and se > 0:
        over = abs(difference) / se
        verdict = "within noise" if over <= WITHIN_NOISE_STDERRS else "not within noise"
        return text + f", {fmt(over, 3)} particle standard errors — {verdict}."
    return text + "."


def steady_verdict(imbalance_over_stderr):
    # In a steady state the two walls carry the same heat flow.
    if not finite(imbalance_over_stderr):
        return "no error estimate."
    if abs(imbalance_over_stderr) <= WITHIN_NOISE_STDERRS:
        return "the same flow within errors, as in a steady state."
    return (f"more than {fmt(WITHIN_NOISE_STDERRS, 2)} standard errors apart, so not a steady "
            "state within errors (the fluid still heating or cooling).")


def rayleigh_explanation(convection, summaries, twins, transport_summary):
    """Why the particle stage's Ra and Pr differ from the twins': each uses other coefficients
    at another temperature (the numbers named from the files)."""
    parts = []
    if convection:
        parts.append(
            "The particle stage's Ra and Pr are estimates made before any measurement: the "
            "kinetic theory's coefficients with g(r) = 1 at the mean wall temperature "
            f"{fmt(number(convection, 'mean_wall_temperature', optional=True))} T0 and "
            "alpha = 1/T (particle/summary.json, results.convection).")
    d = lookup(summaries.get("nominal"), "dimensionless")
    if d:
        state = lookup(transport_summary, "results", "state_point", optional=True) or {}
        temperature = number(state, "temperature", optional=True)
        parts.append(
            "The twins' Ra and Pr use the coefficients the twins run with: the transport "
            "stage's (measured where measured: Transport/Source)"
            + (f" at the particle fluid's mean temperature {fmt(temperature)} T0"
               if finite(temperature) else "")
            + f" (nu {fmt(number(d, 'kinematic_viscosity_nu', optional=True))}, chi "
            f"{fmt(number(d, 'thermal_diffusivity_chi', optional=True))}), over the nominal dT "
            f"{fmt(number(d, 'temperature_difference', optional=True))} and H "
            f"{fmt(number(d, 'height_H', optional=True))}.")
        if convection:
            parts.append("So the columns differ by the estimated against the measured "
                         "coefficients and by the temperature they are taken at; the twins' "
                         "numbers are the ones the comparison rests on.")
        if "calibrated" in twins:
            parts.append("The calibrated twin has the nominal twin's coefficients and dT: "
                         "its Ra and Pr are the same; only its walls differ.")
    return " ".join(parts) or "No dimensionless numbers were recorded."


class RunFiles:
    """A run directory's files, read once, and what several sections take from them."""

    def __init__(self, run_dir):
        self.directory = run_dir
        compare_dir = os.path.join(run_dir, "compare")
        self.metrics = metrics = read_json(os.path.join(compare_dir, "metrics.json"))
        self.bins = read_table(os.path.join(compare_dir, "bins.csv"))
        self.profiles = read_table(os.path.join(compare_dir, "profiles.csv"))
        self.series = read_table(os.path.join(compare_dir, "error_vs_time.csv"))
        self.particle_summary = read_json(os.path.join(run_dir, "particle", "summary.json"))
        # Every run has a nominal twin; a calibrated one only where the scene has thermal walls.
        self.twins = twins = [
            t for t in TWINS
            if isinstance(lookup(metrics, "twins", t, optional=t == "calibrated"), dict)]
        self.summaries = {
            "nominal": read_json(os.path.join(run_dir, "continuum", "summary.json")),
            "calibrated": read_json(os.path.join(run_dir, "continuum_calibrated", "summary.json"),
                                    optional="calibrated" not in twins)}
        self.particle = lookup(metrics, "particle") or {}
        # What the compare stage writes for some scenes only: velocity distances with a positive
        # velocity scale (a flow to compare), density distances beside a low-Mach twin, Nusselt
        # numbers with a heated direction.
        self.optional_field = {"temperature": False,
                               "velocity": not number(metrics, "velocity_scale") > 0,
                               "density": True}
        self.nu_optional = heat_flow_optional(self.particle)
        self.geometry = RunGeometry(metrics, self.particle_summary, self.summaries["nominal"],
                                    self.bins)
        self.case = lookup(metrics, "case") or lookup(self.particle_summary, "case") or \
            os.path.basename(os.path.abspath(run_dir))
        self.excluded = number(metrics, "wall_layer_excluded")
        # The particle stage's estimates need gravity and a heated direction; the measured Mach
        # number a flow.
        self.convection = lookup(lookup(self.particle_summary, "results"), "convection",
                                 optional=True)

    def twin_number(self, t, key):
        """A Nusselt number of metrics.json's twin t."""
        return number(self.metrics, "twins", t, key, optional=self.nu_optional)

    def has_density(self):
        """Whether a twin has density distances (a low-Mach twin)."""
        return any(lookup(self.metrics, "twins", t, "density", optional=True) for t in self.twins)


def report_run(run_dir, out_dir):
    run = RunFiles(run_dir)
    doc = Document(f"Twin comparison: {run.case}")
    verdict_section(doc, run.metrics)
    doc.paragraph(f"Run directory: {os.path.abspath(run_dir)}. Twins compared: "
                  + (", ".join(TWIN_LABEL[t] for t in run.twins) or "none") + ". " + UNITS_NOTE
                  + "." + ensemble_sentence(run.particle_summary))
    dimensionless_numbers_section(doc, run)
    what_was_compared_section(doc, run)
    distances_section(doc, run)
    particle_heat_flow_section(doc, run.particle)
    wall_temperature_jumps_section(doc, run)
    gap_explained_section(doc, run)
    wall_layer_table(doc, run.particle_summary, run.summaries.get("calibrated"))
    continuum_accuracy(doc, run.summaries, run.twins)
    figures_section(doc, run, out_dir)
    write_documents(doc, out_dir)


def ensemble_sentence(particle_summary):
    """The sentence naming a merged ensemble (Particle/Ensemble > 1); "" for one run."""
    ensemble = lookup(lookup(particle_summary, "results"), "ensemble", optional=True)
    if not isinstance(ensemble, dict):
        return ""
    seeds = ensemble.get("seeds") or []
    return (f" The particle stage: an ensemble of {ensemble.get('realisations')} realisations "
            f"(seeds {', '.join(str(s) for s in seeds)}; particle/realisations/), merged: each "
            f"error {ensemble.get('error_rule', '')}.")


def verdict_section(doc, metrics):
    """The compare stage's verdict lines, when it wrote any."""
    verdict = [line for line in (lookup(metrics, "verdict", optional=True) or [])
               if isinstance(line, str)]
    if verdict:
        doc.heading("Verdict")
        doc.bullets(verdict + prediction_lines(metrics))


def prediction_lines(metrics):
    """The nominal twin against the prediction suite's fixed tolerances (compare's "prediction"
    block), beside the strict verdict; none for a run from before it."""
    prediction = lookup(metrics, "prediction", optional=True)
    if not isinstance(prediction, dict):
        return []
    failed = [name for name in ("nusselt", "temperature", "velocity", "density")
              if isinstance(prediction.get(name), dict) and not prediction[name].get("pass")]
    rule = prediction.get("rule", "")
    if prediction.get("pass"):
        return [f"prediction tolerances ({rule}): met"]
    return [f"prediction tolerances ({rule}): not met ({', '.join(failed)})"]


def dimensionless_numbers_section(doc, run):
    """The Ra and Pr of each column, each from the stage that states it, and why they differ."""
    convection = run.convection
    rows = []
    if convection:
        rows.append(["particle (estimate, particle/summary.json)",
                     fmt(number(convection, "rayleigh")), fmt(number(convection, "prandtl")),
                     fmt(number(convection, "mach_measured", optional=True), 3),
                     fmt(number(convection, "delta_T_over_T"), 3), "–"])
    for twin in TWINS:
        d = lookup(run.summaries[twin], "dimensionless")
        if d:
            stage = "continuum_calibrated" if twin == "calibrated" else "continuum"
            rows.append([f"{TWIN_LABEL[twin]} ({stage}/summary.json)",
                         fmt(number(d, "rayleigh")), fmt(number(d, "prandtl")),
                         "–", "–", fmt(number(d, "epsilon"), 3)])
    if rows:
        doc.heading("Dimensionless numbers: which Ra and Pr each column uses")
        doc.table(["source", "Ra", "Pr", "Mach (measured)", "dT/T", "epsilon"], rows)
        doc.paragraph(rayleigh_explanation(convection, run.summaries, run.twins,
                                           read_json(os.path.join(run.directory, "transport",
                                                                  "summary.json"),
                                                     optional=True)))


def what_was_compared_section(doc, run):
    """The bins, the wall layer left out, and the scales the distances are in."""
    metrics = run.metrics
    doc.heading("What was compared")
    counts = lookup(metrics, "bins") or []
    doc.bullets([
        f"Bins: {' × '.join(str(int(c)) for c in counts)}; interior bins (counted in the "
        f"distances): {fmt(number(metrics, 'interior_bins'))}.",
        f"Wall layer: requested {fmt(number(metrics, 'wall_layer'))} rc; excluded thickness "
        f"{fmt(run.excluded)} rc (whole bins) at every wall.",
        f"Temperature scale dT = {fmt(number(metrics, 'temperature_scale'))} T0; velocity scale "
        f"U = {fmt(number(metrics, 'velocity_scale'))} rc/tau (the nominal twin's largest speed). "
        "L2 and max distances below are in these units.",
        f"Fields: {lookup(metrics, 'temperature_field') or 'temperature'}.",
    ] + ([f"Density scale n0 = {fmt(number(metrics, 'density_scale'))} rc^-d (the mean number "
          "density), for the low-Mach twin's n(P, T) against the particles' bin density."]
         if run.has_density() else []))


def distances_section(doc, run):
    """The metrics, one column per twin, and whether each difference is within noise."""
    if not run.twins:
        return
    doc.heading("Distances between the twins")
    doc.table(["quantity"] + [TWIN_LABEL[t] for t in run.twins], distance_rows(run))
    sentences = within_noise_sentences(run)
    bound = fmt(WITHIN_NOISE_STDERRS, 2)
    doc.paragraph(f"Within noise? A difference counts as within noise when the L2 exceeds the "
                  f"noise by at most {bound} of its standard errors; where the twin's inputs "
                  "were measured, the noise is combined with the L2 their errors give the twin "
                  "(its fields re-solved with each input moved by its error) (for Nu: when "
                  f"|Nu particle − Nu twin| is at most {bound} "
                  "standard errors: the particle's, combined with the twin's where its "
                  "coefficients were measured).")
    doc.bullets(sentences)


def distance_rows(run):
    """The distances table's rows: each field's distances, then the Nusselt numbers."""
    metrics, twins, particle = run.metrics, run.twins, run.particle
    table_rows = []

    def row(label, values):
        table_rows.append([label] + values)

    for field, scale in (("temperature", "dT"), ("velocity", "U"), ("density", "n0")):
        d = {t: lookup(metrics, "twins", t, field, optional=run.optional_field[field])
             for t in twins}
        if not any(d.values()):
            continue
        row(f"{field} L2 / {scale}",
            [fmt_pm(number(d[t], "l2"), number(d[t], "l2_stderr")) for t in twins])
        row(f"{field} noise / {scale}", [fmt(number(d[t], "noise")) for t in twins])
        row(f"{field} excess over noise / {scale}",
            [fmt(number(d[t], "excess_over_noise")) for t in twins])
        row(f"{field} max / {scale} (at the bin centre [rc])",
            [f"{fmt_pm(number(d[t], 'max'), number(d[t], 'max_stderr'))} at "
             f"({', '.join(fmt(v, 3) for v in (lookup(d[t], 'max_at') or [])[:run.geometry.dim])})"
             for t in twins])
    row("Nu particle ± stderr",
        [fmt_pm(number(particle, "nusselt", optional=run.nu_optional),
                number(particle, "nusselt_stderr", optional=run.nu_optional))] * len(twins))
    row("Nu twin ± stderr from its measured coefficients and Kapitza conductances (heat "
        "flux / the nominal conduction flux, as the particle's)",
        [fmt_pm(run.twin_number(t, "nusselt"),
                run.twin_number(t, "nusselt_stderr_from_coefficients")) for t in twins])
    row("Nu twin (its own dT)", [fmt(run.twin_number(t, "nusselt_own")) for t in twins])
    row("Nu particle − twin",
        [fmt(run.twin_number(t, "nusselt_particle_minus_twin")) for t in twins])
    row("Nu relative difference",
        [fmt_percent(run.twin_number(t, "nusselt_relative_difference")) for t in twins])
    row("Ra of the twin", [fmt(number(metrics, "twins", t, "rayleigh")) for t in twins])
    return table_rows


def within_noise_sentences(run):
    """Per twin: each field's distance against the noise and the Nusselt gap against the
    errors; then what gravity's stratification alone makes of the density distance."""
    metrics = run.metrics
    sentences = []
    for t in run.twins:
        for field in ("temperature", "velocity", "density"):
            distance = lookup(metrics, "twins", t, field, optional=run.optional_field[field])
            if distance:
                sentences.append(within_noise_sentence(f"{field}, {TWIN_LABEL[t]}", distance))
        s = nusselt_sentence(t, lookup(metrics, "twins", t), run.particle,
                             optional=run.nu_optional)
        if s:
            sentences.append(s)
    stratification = number(run.convection, "stratification_g_H_over_c2")
    if run.has_density() and finite(stratification):
        # n ~ exp(-m g z / kT): across the height a linear profile of relative slope
        # g H / c^2, whose rms over the box is that / sqrt(12). The low-Mach twin's
        # thermodynamic pressure is uniform: it has no hydrostatic stratification.
        sentences.append(
            f"density: the particle fluid is stratified by gravity (g H / c^2 = "
            f"{fmt(stratification, 3)}: n ~ exp(−m g z / kT)), which the low-Mach twin "
            "leaves out (its thermodynamic pressure is uniform); that alone makes an rms "
            f"density difference of ~{fmt(stratification / math.sqrt(12), 2)} n0.")
    return sentences


def particle_heat_flow_section(doc, particle):
    """The particle's Nusselt number and whether its two walls carry the same heat flow."""
    if not finite(number(particle, "nusselt", optional=True)):
        return
    doc.heading("Particle heat flow")
    doc.bullets([
        f"Nu = {fmt_pm(number(particle, 'nusselt'), number(particle, 'nusselt_stderr'))} "
        "(mean of the two walls; heat flux "
        f"{fmt_pm(number(particle, 'heat_flux'), number(particle, 'heat_flux_stderr'))} "
        "k T0 / (rc^(d-1) tau)).",
        f"hot wall Nu = {fmt(number(particle, 'nusselt_hot_wall'))}, cold wall Nu = "
        f"{fmt(number(particle, 'nusselt_cold_wall'))}: they differ by "
        f"{fmt(number(particle, 'wall_imbalance_over_stderr'), 3)} standard errors: "
        + steady_verdict(number(particle, "wall_imbalance_over_stderr")),
    ])


def wall_temperature_jumps_section(doc, run):
    """Each thermal wall's temperature against the particle fluid's there, beside the calibrated
    twin's wall temperature."""
    jumps = lookup(run.particle, "wall_temperature_jumps") or {}
    if not jumps:
        return
    doc.heading("Wall temperature jumps (particle)")
    calibrated_parameters = lookup(run.summaries["calibrated"], "case_parameters")
    rows = []
    for wall, j in jumps.items():
        axis, side = wall.split("_", 1) if "_" in wall else (wall, "")
        calibrated_wall = lookup(
            calibrated_parameters,
            f"Scene/{axis} boundaries/{side.capitalize()} wall temperature")
        rows.append([wall, fmt(number(j, "wall_temperature")),
                     fmt_pm(number(j, "fluid_temperature_at_wall"),
                            number(j, "fluid_temperature_at_wall_stderr")),
                     fmt(number(j, "jump")), fmt(number(j, "extrapolated_from_distance")),
                     fmt(to_float(calibrated_wall)) if calibrated_wall else "–"])
    doc.table(["wall", "wall T [T0]", "fluid T at the wall [T0]", "jump = wall − fluid [T0]",
               "extrapolated from [rc]", "calibrated twin's wall T [T0]"], rows)
    doc.paragraph("The fluid's temperature at a wall is extrapolated linearly from the first "
                  "two bin layers beyond the wall layer (compare stage).")


def gap_explained_section(doc, run):
    """With both twins: how much of each particle–continuum gap the calibration removes, and the
    parameters it changed."""
    metrics, twins = run.metrics, run.twins
    if not ("nominal" in twins and "calibrated" in twins):
        return
    doc.heading("How much of the particle–continuum gap each correction explains")
    gap_rows = []

    def gap(label, nominal_value, calibrated_value):
        if finite(nominal_value) and finite(calibrated_value):
            explained = 1 - calibrated_value / nominal_value if nominal_value != 0 else math.nan
            gap_rows.append([label, fmt(nominal_value), fmt(calibrated_value),
                             fmt_percent(explained)])

    for field, scale in (("temperature", "dT"), ("velocity", "U"), ("density", "n0")):
        distance = {t: lookup(metrics, "twins", t, field, optional=run.optional_field[field])
                    for t in twins}
        gap(f"{field} L2 / {scale}", number(distance["nominal"], "l2"),
            number(distance["calibrated"], "l2"))
        gap(f"{field} excess over noise / {scale}",
            number(distance["nominal"], "excess_over_noise"),
            number(distance["calibrated"], "excess_over_noise"))
    gap("|Nu particle − Nu twin|", abs(run.twin_number("nominal", "nusselt_particle_minus_twin")),
        abs(run.twin_number("calibrated", "nusselt_particle_minus_twin")))
    doc.table(["gap", "nominal twin", f"calibrated twin ({calibration_text(metrics)})",
               "fraction explained = 1 − calibrated / nominal"], gap_rows)
    differences = parameter_differences(run.summaries["nominal"], run.summaries["calibrated"])
    if differences:
        doc.paragraph("The calibrated twin's parameters that differ from the nominal twin's "
                      "(continuum*/summary.json): " + "; ".join(
                          f"{k}: {a} → {b}" for k, a, b in differences) +
                      ". The fraction explained is the part of each gap that this change "
                      "removes; a negative fraction means it made the gap larger.")


def figures_section(doc, run, out_dir):
    """The figures there is data for, each with its caption."""
    bins, profiles, series, twins = run.bins, run.profiles, run.series, run.twins
    doc.heading("Figures")
    if bins and bins.rows and bins.has("T_particle", optional=False):
        reference, cut_text = figure_fields(out_dir, bins, run.geometry, twins, run.metrics)
        where = f"; 3D: {cut_text}" if cut_text else ""
        difference = (f", and particle − {TWIN_LABEL[reference]} on a diverging scale (×: the "
                      "largest interior difference, metrics.json max_at)" if reference else "")
        doc.figure("fields.png",
                   "Bin-averaged temperature: particle (T_kinetic)"
                   + "".join(", " + TWIN_LABEL[t] for t in twins) + " on one colour scale"
                   + difference + ". Arrows: bin velocities (one scale for all maps, key on the "
                   f"particle map). Hatched: the wall layer ({fmt(run.excluded)} rc) left out of "
                   f"the distances{where}. {UNITS_NOTE}.")
    if bins and bins.rows and any(bins.has(f"density_{t}") for t in twins):
        reference, _ = figure_fields(out_dir, bins, run.geometry, twins, run.metrics, "density")
        doc.figure("density.png",
                   "Bin-averaged number density: particle and the low-Mach twin's n(P, T) "
                   "(thermodynamic pressure P from the closed cavity's mass) on one colour scale"
                   + (f", and particle − {TWIN_LABEL[reference]}" if reference else "")
                   + f". Arrows and hatching as above. {UNITS_NOTE}.")
    if profiles and profiles.rows:
        titles = figure_profiles(out_dir, profiles, run.geometry, run.metrics, twins,
                                 run.excluded)
        doc.figure("profiles.png",
                   "Mid-line profiles (" + "; ".join(titles) + "), compare/profiles.csv ("
                   + ("; ".join(profiles.comments) or "mid-line profiles") + "): particle "
                   "bins with their block standard errors, the twins as lines; grey: the "
                   "excluded wall layer; squares: the walls' temperatures; diamonds: the particle "
                   f"fluid's temperature extrapolated to the wall. {UNITS_NOTE}.")
    # Written by the particle stage for a scene with walls.
    layers = read_table(os.path.join(run.directory, "particle", "wall_layers.csv"),
                        optional=True)
    if layers and layers.rows:
        figure_wall_layers(out_dir, layers, run.particle_summary)
        doc.figure("wall_layers.png",
                   "The particle fluid in the layer at each wall (particle/wall_layers.csv, "
                   "slices parallel to the wall, block standard errors): number density, kinetic "
                   "temperature and the velocity along the wall against the distance h from the "
                   "wall plane; dashed: each wall's effective position (the Gibbs depth of its "
                   "density profile, where Compare/Effective walls puts the calibrated twin's "
                   f"wall). {UNITS_NOTE}.")
    if series and series.rows:
        fields = figure_error_vs_time(out_dir, series, run.metrics, twins)
        doc.figure("error_vs_time.png",
                   "L2 distance of the cumulative particle average to each twin against the "
                   "particle run's wall-clock time (log-log), with standard errors; solid grey: "
                   "the noise (the L2 two identical twins would show through the particle's "
                   "statistical error); dotted: the floor, the final excess over noise "
                   "(metrics.json).")
        floor_text(doc, series, run.metrics, twins, fields, run.particle, run.summaries)


def continuum_accuracy(doc, summaries, twins):
    """The twins' own errors beside the particle's: discretisation (Nu against mesh level; the
    last change bounds the error of a converging sequence) and the measured coefficients'."""
    rows = []
    for twin in twins:
        # A transient twin has no mesh study.
        for level in lookup(lookup(summaries[twin], "results"), "mesh_study", optional=True) or []:
            cells = "×".join(str(int(c)) for c in (lookup(level, "cells") or []))
            change = number(level, "change_in_nusselt")
            rows.append([TWIN_LABEL[twin], fmt(number(level, "level"), 2), cells,
                         fmt(number(level, "nusselt"), 7),
                         fmt(change, 2) if number(level, "level") > 0 else "–",
                         fmt(number(level, "wall_time_s"), 3)])
    if not rows:
        return
    doc.heading("The continuum twins' own errors")
    doc.paragraph("Mesh study (continuum*/summary.json, results.mesh_study): each level halves the "
                  "cells; the change in Nu from the level before bounds the discretisation error "
                  "of the finest level when the changes fall geometrically.")
    doc.table(["twin", "level", "cells", "Nu (own dT)", "change", "wall s"], rows)
    sentences = []
    for twin in twins:
        # Only a steady twin with measured coefficients (or Kapitza errors) has one.
        u = lookup(summaries[twin], "coefficient_uncertainty", optional=True)
        if not u:
            continue
        names = ["conductivity", "viscosity"] + [f"kapitza_{a}_{s}" for a in "xyz"
                                                 for s in ("lower", "upper")]
        parts = [f"{name.replace('_', ' ')} "
                 f"{fmt_pm(number(u, name, 'value'), number(u, name, 'stderr'))} moves the "
                 f"heat flux by {fmt_percent(number(u, name, 'heat_flux_relative_change'))} per "
                 "standard error" for name in names if lookup(u, name, optional=True)]
        sentences.append(f"{TWIN_LABEL[twin]}: " + "; ".join(parts) + "; together ± "
                         f"{fmt_percent(number(u, 'heat_flux_relative_stderr'))}.")
    if sentences:
        doc.paragraph("The measured coefficients' errors (transport stage, from the spread of "
                      "repeated runs) and the Kapitza conductances' (from the particle walls' "
                      "heat-flux and fluid-temperature errors), one more solve each:")
        doc.bullets(sentences)


def parameter_differences(nominal_summary, calibrated_summary):
    """(key, nominal value, calibrated value) for every case parameter the twins differ in (keys
    enumerated from the files, none named here: plain dict reads)."""
    a = lookup(nominal_summary, "case_parameters") or {}
    b = lookup(calibrated_summary, "case_parameters") or {}
    def shown(value):
        # An empty value is a key the twin leaves unset: say so, never an empty "from".
        return "(not set)" if value in (None, "") else value
    return [(k, shown(a.get(k)), shown(b.get(k))) for k in sorted(set(a) | set(b))
            if a.get(k) != b.get(k)]


def floor_text(doc, series, metrics, twins, fields, particle, summaries):
    import numpy as np
    seconds = series.numbers("wall_seconds")
    items = []
    for field in fields:
        noise = series.numbers(f"{field}_noise") if series.has(f"{field}_noise",
                                                               optional=False) else None
        if noise is not None and np.isfinite(noise).sum() >= 2:
            items.append(f"{field} noise: {fmt(noise[0], 3)} at {fmt(seconds[0], 3)} s, "
                         f"{fmt(noise[-1], 3)} at {fmt(seconds[-1], 3)} s.")
        for twin in twins:
            floor = number(metrics, "twins", twin, field, "excess_over_noise")
            if finite(floor):
                items.append(f"{field} floor, {TWIN_LABEL[twin]}: {fmt(floor, 3)} (final L2 "
                             f"{fmt(number(metrics, 'twins', twin, field, 'l2'), 3)}).")
    doc.paragraph("The floor. The noise falls as 1/√t with sampling time; what stays as it falls "
                  "is the twins' physical difference, the excess over noise. Measured:")
    doc.bullets(items)
    # What sets the floor, in the numbers of this run.
    causes = []
    jumps = lookup(particle, "wall_temperature_jumps") or {}
    scale = number(metrics, "temperature_scale")
    nominal_range = (number(summaries["nominal"], "results", "temperature_min"),
                     number(summaries["nominal"], "results", "temperature_max"))
    if jumps:
        causes.append("Wall temperature jumps of the particle fluid: " + "; ".join(
            f"{wall}: {fmt(number(j, 'jump'), 3)} T0 "
            f"({fmt_percent(number(j, 'jump') / scale)} of dT)"
            for wall, j in jumps.items()) +
            (f". The nominal twin's temperature spans {fmt(nominal_range[0], 3)} … "
             f"{fmt(nominal_range[1], 3)} T0, the walls are at " +
             ", ".join(fmt(number(j, "wall_temperature"), 3) for j in jumps.values()) +
             " T0: the jumps are part of its floor." if all(finite(v) for v in nominal_range)
             else "."))
    if "nominal" in twins and "calibrated" in twins:
        n_floor = number(metrics, "twins", "nominal", "temperature", "excess_over_noise")
        c_floor = number(metrics, "twins", "calibrated", "temperature", "excess_over_noise")
        if finite(n_floor) and finite(c_floor) and n_floor > 0:
            causes.append(f"With {calibration_text(metrics)} (calibrated twin) the "
                          f"temperature floor goes from {fmt(n_floor, 3)} to {fmt(c_floor, 3)} "
                          f"({fmt_percent(c_floor / n_floor)} of the nominal twin's): the rest of "
                          "the calibrated twin's floor is what that wall condition does not "
                          "explain.")
    for twin in twins:
        rel = number(metrics, "twins", twin, "nusselt_relative_difference",
                     optional=heat_flow_optional(particle))
        if finite(rel):
            causes.append(f"Heat flow: the particle's Nu differs from the {TWIN_LABEL[twin]}'s by "
                          f"{fmt_percent(rel)} of the twin's.")
    if causes:
        doc.paragraph("What sets it, from this run's numbers:")
        doc.bullets(causes)
