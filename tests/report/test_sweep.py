"""report.sweep: Pareto front, series groups, the walls' slip, and the optional metric columns."""

import os
import tempfile
import unittest

import report_path  # noqa: F401  (compare/ on sys.path)
from report.data import MissingKey, Table, cell, strict_mode
from report.document import Document
from report.sweep import (DE_VAHL_DAVIS_NUSSELT, Sweep, in_range, landing_summary, metric,
                          pareto_front, rayleigh_miss, source_style, sweep_groups, verdict_section,
                          walls_no_slip)


class Pareto(unittest.TestCase):
    def test_front_sorted_by_cost(self):
        points = [(10, 0.5), (1, 0.9), (5, 0.2), (6, 0.3), (20, 0.1)]
        # (6, 0.3) is beaten by (5, 0.2); (10, 0.5) by (5, 0.2) too.
        self.assertEqual(pareto_front(points), [1, 2, 4])

    def test_ties_are_kept(self):
        self.assertEqual(pareto_front([(1, 1), (1, 1), (2, 2)]), [0, 1])


class Groups(unittest.TestCase):
    rows = [{"k": "b", "x": "1"}, {"k": "a", "x": "2"}, {"k": "c", "x": "3"}, {"k": "a", "x": "4"}]

    def test_grid_order_then_first_seen(self):
        groups = sweep_groups(self.rows, "k", ["a", "b"])
        self.assertEqual([label for label, _ in groups], ["k = a", "k = b", "k = c"])
        self.assertEqual([r["x"] for r in groups[0][1]], ["2", "4"])

    def test_one_group_without_a_series_key(self):
        self.assertEqual(sweep_groups(self.rows, None, []), [("", self.rows)])

    def test_source_style(self):
        self.assertEqual(source_style(0, "particle"), ("o", "-"))
        self.assertEqual(source_style(2, "noise"), ("", ":"))
        self.assertEqual(source_style(6, "x"), source_style(0, "y"))  # cycles


class WallsNoSlip(unittest.TestCase):
    def grid(self, **slips):
        parameters = {"Scene/z boundaries/Type": "periodic"}
        for axis, slip in slips.items():
            parameters[f"Scene/{axis} boundaries/Type"] = "walls"
            if slip is not None:
                parameters[f"Scene/{axis} boundaries/Slip"] = slip
        return {"base_parameters": parameters}

    def test_answers(self):
        self.assertTrue(walls_no_slip(self.grid(x="no-slip", y="no-slip")))
        self.assertFalse(walls_no_slip(self.grid(x="no-slip", y="free-slip")))
        self.assertIsNone(walls_no_slip(self.grid()))  # no walls
        self.assertIsNone(walls_no_slip(self.grid(x=None)))  # slip not stated


class RayleighTargets(unittest.TestCase):
    rows = [{"point": "000", "status": "done", "target_rayleigh": "100", "rayleigh": "101.5"},
            {"point": "001", "status": "done", "target_rayleigh": "1e4", "rayleigh": "9600"},
            {"point": "002", "status": "failed", "target_rayleigh": "3000", "rayleigh": ""}]

    def test_miss_is_achieved_over_target_minus_one(self):
        self.assertAlmostEqual(rayleigh_miss(self.rows[0]), 0.015)
        self.assertAlmostEqual(rayleigh_miss(self.rows[1]), -0.04)
        self.assertNotEqual(rayleigh_miss(self.rows[2]), rayleigh_miss(self.rows[2]))  # NaN

    def test_summary_names_the_farthest_point(self):
        text = landing_summary(self.rows)
        self.assertIn("2 point(s)", text)
        self.assertIn("point 001", text)
        self.assertIn("-4.0 %", text)
        self.assertIsNone(landing_summary([self.rows[2]]))

    def test_benchmark_only_within_the_sweeps_range(self):
        self.assertEqual(in_range(DE_VAHL_DAVIS_NUSSELT, [100, 3000, 1e4]),
                         [(1e3, 1.118), (1e4, 2.243)])
        self.assertEqual(in_range(DE_VAHL_DAVIS_NUSSELT, [200, 500]), [])
        self.assertEqual(in_range(DE_VAHL_DAVIS_NUSSELT, []), [])


class Columns(unittest.TestCase):
    def test_metrics_optional_own_columns_required(self):
        folder = tempfile.mkdtemp()
        path = os.path.join(folder, "sweep.csv")
        with open(path, "w", encoding="utf-8") as f:
            f.write("point,status,reason,exit_code,wall_seconds\n000,failed,,4,3\n")
        row = Table(path).rows[0]
        with strict_mode():
            self.assertEqual(metric(row, "nusselt_particle"), "")  # no point finished
            self.assertEqual(cell(row, "status"), "failed")
            with self.assertRaises(MissingKey):
                cell(row, "target_rayleigh")


class Verdict(unittest.TestCase):
    def test_counts_the_points_own_verdicts(self):
        folder = tempfile.mkdtemp()
        with open(os.path.join(folder, "sweep.csv"), "w", encoding="utf-8") as f:
            f.write("point,status,reason,exit_code,Particle/Seed,wall_seconds,"
                    "within_errors_nominal,prediction_pass\n"
                    "000,done,,0,1,3,true,true\n001,done,,0,2,3,false,true\n"
                    "002,failed,unstable,4,3,1,,\n")
        doc = Document("sweep")
        verdict_section(doc, Sweep(folder))
        self.assertEqual(doc.blocks[0], ("heading", 2, "Verdict"))
        first, second = doc.blocks[1][1]
        self.assertTrue(first.startswith("verdict: 2 of 3 points done"))
        self.assertIn("within errors (compare's strict verdict) at 1 of 2", first)
        self.assertIn("within the prediction tolerances at 2 of 2", first)
        self.assertIn("002 (failed)", second)


if __name__ == "__main__":
    unittest.main()
