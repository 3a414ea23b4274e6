"""report.run: the verdict sentences, the scene's geometry, and what a run report may lack."""

import math
import os
import unittest

import report_path  # noqa: F401  (compare/ on sys.path)
from report import data
from report.data import MissingKey, strict_mode
from report.document import Document
from report.run import (calibration_text, heat_flow_optional, nusselt_sentence,
                        parameter_differences, rayleigh_explanation, steady_verdict,
                        within_noise_sentence)
from report.run_figures import RunGeometry, wall_layer_table


def metrics_json(tree):
    return data._attach(tree, "compare/metrics.json")


class WithinNoise(unittest.TestCase):
    def test_within_noise(self):
        # (0.0300 - 0.0250) / 0.0050 = 1 standard error above the noise.
        self.assertEqual(
            within_noise_sentence("temperature, nominal twin",
                                  {"l2": 0.030, "l2_stderr": 0.005, "noise": 0.025}),
            "temperature, nominal twin: L2 = 0.0300 ± 0.0050 against a noise of 0.025, 1 "
            "standard errors above it — within noise.")

    def test_not_within_noise(self):
        self.assertEqual(
            within_noise_sentence("t", {"l2": 0.232, "l2_stderr": 0.012, "noise": 0.0233}),
            "t: L2 = 0.232 ± 0.012 against a noise of 0.0233, 17.4 standard errors above it — "
            "not within noise: a difference between the twins.")

    def test_two_standard_errors_is_still_within(self):
        sentence = within_noise_sentence("t", {"l2": 0.3, "l2_stderr": 0.1, "noise": 0.1})
        self.assertTrue(sentence.endswith("2 standard errors above it — within noise."), sentence)

    def test_below_the_noise(self):
        sentence = within_noise_sentence("t", {"l2": 0.02, "l2_stderr": 0.01, "noise": 0.03})
        self.assertIn("1 standard errors below it — within noise.", sentence)

    def test_without_a_standard_error(self):
        self.assertTrue(within_noise_sentence("t", {"l2": 0.02, "noise": 0.03})
                        .endswith(" — within noise."))
        self.assertTrue(within_noise_sentence("t", {"l2": 0.04, "l2_stderr": None, "noise": 0.03})
                        .endswith(" — above the noise (no standard error)."))

    def test_the_twins_inputs_join_the_noise(self):
        # hypot(0.03, 0.04) = 0.05; (0.06 - 0.05) / 0.01 = 1 standard error above it.
        sentence = within_noise_sentence(
            "t", {"l2": 0.06, "l2_stderr": 0.01, "noise": 0.03, "noise_twin": 0.04})
        self.assertEqual(
            sentence, "t: L2 = 0.060 ± 0.010 against a noise of 0.03 and the twin's 0.04 from its "
            "measured inputs' errors (0.05 together), 1 standard errors above it — within errors.")
        sentence = within_noise_sentence(
            "t", {"l2": 0.2, "l2_stderr": 0.01, "noise": 0.03, "noise_twin": 0.04})
        self.assertTrue(sentence.endswith("not within errors: a difference between the twins."),
                        sentence)

    def test_without_l2(self):
        self.assertEqual(within_noise_sentence("t", {"noise": 0.03}), "t: no L2 in metrics.json.")


class Nusselt(unittest.TestCase):
    particle = {"nusselt": 0.58, "nusselt_stderr": 0.006}

    def test_combined_errors(self):
        # |0.004| / hypot(0.003, 0.004) = 0.8 combined standard errors.
        twin = {"nusselt_particle_minus_twin": 0.004, "nusselt_relative_difference": 0.007,
                "nusselt_stderr_from_coefficients": 0.004}
        self.assertEqual(
            nusselt_sentence("calibrated", twin, {"nusselt_stderr": 0.003}),
            "Nusselt number, calibrated twin: particle − twin = 0.004 (0.7 % of the twin's), "
            "0.8 combined standard errors (particle 0.003, twin 0.004 from its measured inputs) "
            "— within the errors.")

    def test_not_within_the_errors(self):
        twin = {"nusselt_particle_minus_twin": -0.86, "nusselt_relative_difference": -0.86,
                "nusselt_stderr_from_coefficients": 0.17}
        self.assertTrue(nusselt_sentence("nominal", twin, {"nusselt_stderr": 0.018})
                        .endswith("— not within the errors."))

    def test_particle_error_only(self):
        twin = {"nusselt_particle_minus_twin": 0.03, "nusselt_relative_difference": 0.05,
                "nusselt_stderr_from_coefficients": None}
        self.assertEqual(
            nusselt_sentence("nominal", twin, {"nusselt_stderr": 0.01}),
            "Nusselt number, nominal twin: particle − twin = 0.03 (5.0 % of the twin's), 3 "
            "particle standard errors — not within noise.")

    def test_no_errors_and_no_difference(self):
        twin = {"nusselt_particle_minus_twin": 0.03, "nusselt_relative_difference": 0.05}
        self.assertTrue(nusselt_sentence("nominal", twin, {}).endswith("of the twin's)."))
        self.assertIsNone(nusselt_sentence("nominal", {}, {}))

    def test_strict_unless_the_scene_has_no_heated_direction(self):
        metrics = metrics_json({"particle": {}, "twins": {"nominal": {"rayleigh": 1e3}}})
        particle = data.lookup(metrics, "particle")
        twin = data.lookup(metrics, "twins", "nominal")
        with strict_mode():
            self.assertTrue(heat_flow_optional(particle))
            self.assertIsNone(nusselt_sentence("nominal", twin, particle, optional=True))
            with self.assertRaises(MissingKey) as raised:
                nusselt_sentence("nominal", twin, particle)
        self.assertEqual(raised.exception.path, ("twins", "nominal", "nusselt_particle_minus_twin"))
        self.assertFalse(heat_flow_optional({"nusselt": 0.5}))


class Sentences(unittest.TestCase):
    def test_steady_verdict(self):
        self.assertEqual(steady_verdict(1.5), "the same flow within errors, as in a steady state.")
        self.assertEqual(steady_verdict(-2.0), "the same flow within errors, as in a steady state.")
        self.assertTrue(steady_verdict(2.5).startswith("more than 2 standard errors apart"))
        self.assertEqual(steady_verdict(math.nan), "no error estimate.")

    def test_calibration_text(self):
        self.assertEqual(calibration_text({"twins": {"calibrated": {"calibration": "Kapitza"}}}),
                         "Kapitza")
        self.assertEqual(calibration_text({"twins": {"calibrated": {}}}),
                         "walls at the fluid's wall temperatures")
        with strict_mode(), self.assertRaises(MissingKey):
            calibration_text(metrics_json({"twins": {"calibrated": {}}}))

    def test_parameter_differences(self):
        nominal = {"case_parameters": {"a": "1", "b": "2", "c": "3"}}
        calibrated = {"case_parameters": {"a": "1", "b": "5", "d": "4"}}
        self.assertEqual(parameter_differences(nominal, calibrated),
                         [("b", "2", "5"), ("c", "3", "(not set)"), ("d", "(not set)", "4")])

    def test_an_empty_value_is_named_not_left_blank(self):
        # The calibrated twin's Kapitza conductances are empty in the nominal twin's case: the
        # line said "Kapitza conductances:  -> 1.30" (issue 29).
        nominal = {"case_parameters": {"Continuum/Kapitza conductances": ""}}
        calibrated = {"case_parameters": {"Continuum/Kapitza conductances": "1.30, 5.0"}}
        self.assertEqual(parameter_differences(nominal, calibrated),
                         [("Continuum/Kapitza conductances", "(not set)", "1.30, 5.0")])


class DimensionlessNumbers(unittest.TestCase):
    def test_explains_which_coefficients_and_temperature_each_column_uses(self):
        convection = {"rayleigh": 3511, "prandtl": 1.1, "mean_wall_temperature": 1.0}
        dimensionless = {"rayleigh": 1955, "prandtl": 0.79, "kinematic_viscosity_nu": 0.29,
                         "thermal_diffusivity_chi": 0.37, "temperature_difference": 1.0,
                         "height_H": 20}
        transport = {"results": {"state_point": {"temperature": 0.814}}}
        text = rayleigh_explanation(convection, {"nominal": {"dimensionless": dimensionless}},
                                    ["nominal", "calibrated"], transport)
        for part in ("estimates", "g(r) = 1", "mean wall temperature 1 T0", "measured",
                     "mean temperature 0.814 T0", "nu 0.29", "chi 0.37", "H 20",
                     "calibrated twin has the nominal twin's coefficients"):
            self.assertIn(part, text)

    def test_without_numbers(self):
        self.assertEqual(rayleigh_explanation(None, {}, [], None),
                         "No dimensionless numbers were recorded.")


class Geometry(unittest.TestCase):
    parameters = {"Scene/Dimension": "2", "Scene/Box size": "20, 10", "Scene/Gravity": "0, -0.02",
                  "Scene/x boundaries/Type": "walls", "Scene/y boundaries/Type": "periodic"}

    def test_heated_from_the_walls_vertical_from_gravity(self):
        metrics = {"bins": [10, 5], "particle": {"wall_temperature_jumps": {
            "x_lower": {"wall_temperature": 1.5}, "x_upper": {"wall_temperature": 0.5}}}}
        geometry = RunGeometry(metrics, {"parameters": self.parameters}, None, None)
        self.assertEqual((geometry.dim, geometry.box, geometry.walled), (2, [20.0, 10.0],
                                                                         [True, False]))
        self.assertEqual((geometry.heated, geometry.vertical), (0, 1))
        self.assertEqual(geometry.plane(), (0, 1, None))

    def test_heated_from_the_continuum_when_no_wall_is_hotter(self):
        metrics = {"bins": [10, 5], "particle": {"wall_temperature_jumps": {}}}
        nominal = {"dimensionless": {"heated_direction": 1}}
        parameters = dict(self.parameters, **{"Scene/Gravity": "0, 0"})
        geometry = RunGeometry(metrics, {"parameters": parameters}, nominal, None)
        self.assertEqual((geometry.heated, geometry.vertical), (1, 0))

    def test_3d_cuts_the_third_axis(self):
        parameters = dict(self.parameters, **{"Scene/Dimension": "3",
                                              "Scene/Box size": "8, 8, 8",
                                              "Scene/Gravity": "0, 0, -1"})
        metrics = {"bins": [4, 4, 4], "particle": {"wall_temperature_jumps": {
            "y_lower": {"wall_temperature": 2}, "y_upper": {"wall_temperature": 1}}}}
        geometry = RunGeometry(metrics, {"parameters": parameters}, None, None)
        self.assertEqual((geometry.heated, geometry.vertical), (1, 2))
        self.assertEqual(geometry.plane(), (1, 2, 0))

    def test_strict_reads_of_the_parameters(self):
        summary = data._attach({"parameters": {"Scene/Box size": "8, 8"}}, "particle/summary.json")
        metrics = metrics_json({"bins": [4, 4], "particle": {"wall_temperature_jumps": {}}})
        with strict_mode(), self.assertRaises(MissingKey) as raised:
            RunGeometry(metrics, summary, None, None)
        self.assertEqual(str(raised.exception),
                         "particle/summary.json: no key 'parameters/Scene/x boundaries/Type'")


class WallLayers(unittest.TestCase):
    def summary(self, walls):
        return data._attach({"results": {"walls": walls}}, "particle/summary.json")

    def test_rows_and_what_may_be_absent(self):
        walls = {"x_lower": {"effective_position": 0.47, "effective_position_stderr": 0.033,
                             "friction_per_area": 1.86, "friction_per_area_stderr": 0.19},
                 "x_upper": {"effective_position": 0.54, "effective_position_stderr": 0.029},
                 "y_lower": {"pressure": 3.9}}  # no layer measured: no row
        calibrated = data._attach({"continuum_parameters": {"boundaries": [
            {"direction": "x", "lower": {"slip_length": 0.22, "kapitza_conductance": 1.24},
             "upper": {}},
            {"direction": "y", "periodic": True}]}}, "continuum_calibrated/summary.json")
        doc = Document("t")
        with strict_mode():
            wall_layer_table(doc, self.summary(walls), calibrated)
        table = next(b for b in doc.blocks if b[0] == "table")
        self.assertEqual(table[2], [["x_lower", "0.470 ± 0.033", "1.86 ± 0.19", "0.22", "1.24"],
                                    ["x_upper", "0.540 ± 0.029", "(free slip)", "none", "none"]])

    def test_no_walls_no_table(self):
        doc = Document("t")
        with strict_mode():
            wall_layer_table(doc, data._attach({"results": {}}, "s.json"), None)
        self.assertEqual(doc.blocks, [])

    def test_a_layer_without_its_error_is_an_error(self):
        with strict_mode(), self.assertRaises(MissingKey) as raised:
            wall_layer_table(Document("t"), self.summary({"x_lower": {"effective_position": 1}}),
                             None)
        self.assertEqual(raised.exception.path,
                         ("results", "walls", "x_lower", "effective_position_stderr"))


if __name__ == "__main__":
    unittest.main()


class Verdict(unittest.TestCase):
    """The report opens with compare's verdict (metrics.json "verdict"): the headline and one
    line per twin, before anything else."""

    def test_the_verdict_comes_first(self):
        import json
        import shutil
        import tempfile
        from report.run import report_run
        fixture = os.path.join(report_path.SOURCE_DIR, "tests", "study", "fixtures",
                               "run_2d_calibrated")
        folder = tempfile.mkdtemp()
        try:
            run_dir = os.path.join(folder, "run")
            shutil.copytree(fixture, run_dir)
            path = os.path.join(run_dir, "compare", "metrics.json")
            with open(path, encoding="utf-8") as f:
                metrics = json.load(f)
            verdict = ["verdict: the calibrated twin matches the particles within errors",
                       "particle vs nominal twin: Nu 0.57 +- 0.01 against 1.29 +- 0.02",
                       "particle vs calibrated twin: Nu 0.57 +- 0.01 against 0.57 +- 0.01"]
            metrics["verdict"] = verdict
            with open(path, "w", encoding="utf-8") as f:
                json.dump(metrics, f)
            out_dir = os.path.join(run_dir, "report")
            os.makedirs(out_dir, exist_ok=True)
            report_run(run_dir, out_dir)
            with open(os.path.join(out_dir, "report.md"), encoding="utf-8") as f:
                text = f.read()
            self.assertEqual(text.split("\n")[2], "## Verdict")
            for line in verdict:
                self.assertIn("- " + line, text)
            self.assertLess(text.index(verdict[2]), text.index("## Dimensionless numbers"))
            self.assertNotIn("nan", text.replace("nano", ""))
            leftovers = [n for n in os.listdir(out_dir) if ".tmp" in n]
            self.assertEqual(leftovers, [])
        finally:
            shutil.rmtree(folder)
