"""report.data: number formatting, the lookup helper (strict and not), JSON and CSV reading."""

import math
import os
import tempfile
import unittest

import report_path  # compare/ on sys.path; FolderTestCase
from report import data
from report.data import (MissingKey, Record, Table, cell, finite, fmt, fmt_percent, fmt_pm,
                         lookup, number, plain, present, read_json, read_table, slug,
                         strict_mode, study_case_name, to_float, varied_keys, with_unit)


def write(folder, name, text):
    path = os.path.join(folder, name)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


class Formatting(unittest.TestCase):
    def test_fmt_significant_digits_without_exponent_in_range(self):
        self.assertEqual(fmt(3.14159), "3.142")
        self.assertEqual(fmt(0.0012346), "0.001235")  # 1e-3 <= |v|: still plain
        self.assertEqual(fmt(12345.6), "12346")
        self.assertEqual(fmt(2.5), "2.5")  # trailing zeros dropped
        self.assertEqual(fmt(100.0), "100")  # and the point with them
        self.assertEqual(fmt(-0.25, 2), "-0.25")

    def test_fmt_exponent_outside_range(self):
        self.assertEqual(fmt(123456.0), "1.235e5")
        self.assertEqual(fmt(0.00012346), "1.235e-4")
        self.assertEqual(fmt(2e-6), "2e-6")

    def test_fmt_special_values(self):
        self.assertEqual(fmt(None), "–")
        self.assertEqual(fmt(math.nan), "–")
        self.assertEqual(fmt(math.inf), "–")
        self.assertEqual(fmt(True), "yes")
        self.assertEqual(fmt(False), "no")
        self.assertEqual(fmt(7), "7")  # an int as is (JSON counts)
        self.assertEqual(fmt(0.0), "0")

    def test_fmt_pm_error_to_two_digits(self):
        self.assertEqual(fmt_pm(0.5730, 0.0056), "0.5730 ± 0.0056")
        self.assertEqual(fmt_pm(18.76, 0.30), "18.76 ± 0.30")
        self.assertEqual(fmt_pm(1234.5, 67.0), "1234 ± 67")
        # Outside 1e-4 .. 1e5 a common power of ten.
        self.assertEqual(fmt_pm(1.5e-5, 2.0e-6), "(1.50 ± 0.20)e-5")
        self.assertEqual(fmt_pm(2.0e6, 3.0e4), "(2.000 ± 0.030)e6")

    def test_fmt_pm_without_a_usable_error(self):
        self.assertEqual(fmt_pm(math.nan, 0.1), "–")
        self.assertEqual(fmt_pm(1.5, math.nan), "1.5")
        self.assertEqual(fmt_pm(1.5, 0.0), "1.5")
        self.assertEqual(fmt_pm(1.5, None), "1.5")

    def test_fmt_percent(self):
        self.assertEqual(fmt_percent(0.0123), "1.2 %")
        self.assertEqual(fmt_percent(-0.8603), "-86.0 %")
        self.assertEqual(fmt_percent(math.nan), "–")

    def test_text_helpers(self):
        self.assertEqual(plain(""), "–")
        self.assertEqual(plain(None), "–")
        self.assertEqual(plain("0.01"), "0.01")
        self.assertEqual(slug("Particle/Time step"), "particle_time_step")
        self.assertEqual(slug("///"), "value")
        self.assertEqual(with_unit("Particle/Time step"), "Particle/Time step [tau]")
        self.assertEqual(with_unit("Particle/Seed"), "Particle/Seed")

    def test_numbers_from_text(self):
        self.assertEqual(to_float("2.5"), 2.5)
        self.assertTrue(math.isnan(to_float("")))
        self.assertTrue(math.isnan(to_float(None)))
        self.assertTrue(finite(1) and finite(2.5))
        self.assertFalse(finite(math.nan) or finite(None) or finite("1"))


class Lookup(unittest.TestCase):
    def setUp(self):
        self.tree = data._attach({"twins": {"nominal": {"l2": 0.5, "max_at": [1, 2]},
                                            "calibrated": None}}, "metrics.json")

    def test_a_path_through_objects_and_lists(self):
        self.assertEqual(lookup(self.tree, "twins", "nominal", "l2"), 0.5)
        self.assertEqual(lookup(self.tree, "twins", "nominal", "max_at", 1), 2)
        self.assertEqual(lookup(self.tree, "twins", "nominal", "max_at", -1), 2)

    def test_missing_is_none_without_strict_mode(self):
        with strict_mode(False):
            self.assertIsNone(lookup(self.tree, "twins", "nominal", "l3"))
            self.assertIsNone(lookup(self.tree, "twins", "nominal", "max_at", 5))
            self.assertTrue(math.isnan(number(self.tree, "twins", "velocity", "l2")))

    def test_strict_mode_names_the_file_and_the_key(self):
        with strict_mode():
            with self.assertRaises(MissingKey) as raised:
                lookup(self.tree, "twins", "nominal", "nusselt_stderr")
        self.assertEqual(raised.exception.source, "metrics.json")
        self.assertEqual(raised.exception.path, ("twins", "nominal", "nusselt_stderr"))
        self.assertEqual(str(raised.exception),
                         "metrics.json: no key 'twins/nominal/nusselt_stderr'")

    def test_strict_mode_path_of_a_nested_record(self):
        # A sub-object passed on knows where it came from.
        nominal = lookup(self.tree, "twins", "nominal")
        with strict_mode():
            with self.assertRaises(MissingKey) as raised:
                number(nominal, "noise")
        self.assertEqual(raised.exception.path, ("twins", "nominal", "noise"))

    def test_strict_mode_stops_at_the_first_missing_step(self):
        with strict_mode():
            with self.assertRaises(MissingKey) as raised:
                lookup(self.tree, "particle", "nusselt")
        self.assertEqual(raised.exception.path, ("particle",))

    def test_optional_keys_and_absent_parents_are_not_errors(self):
        with strict_mode():
            self.assertIsNone(lookup(self.tree, "twins", "nominal", "density", optional=True))
            self.assertIsNone(lookup(None, "anything"))  # an optional file that is absent
            # A JSON null: the key is there; below it nothing is asked of it.
            self.assertIsNone(lookup(self.tree, "twins", "calibrated", "l2"))
            self.assertTrue(math.isnan(number(self.tree, "twins", "calibrated", "l2")))

    def test_present_tells_absent_from_null(self):
        self.assertTrue(present(self.tree, "twins", "calibrated"))
        self.assertFalse(present(self.tree, "twins", "velocity"))
        self.assertFalse(present(None, "twins"))
        self.assertFalse(present({"a": 1}, "a", "b"))

    def test_number_is_a_finite_float_or_nan(self):
        record = Record({"n": 3, "flag": True, "text": "x", "null": None})
        self.assertEqual(number(record, "n"), 3.0)
        self.assertIsInstance(number(record, "n"), float)
        for key in ("flag", "text", "null"):
            self.assertTrue(math.isnan(number(record, key)), key)


class Files(report_path.FolderTestCase):
    def test_read_json_attaches_the_file_to_every_object(self):
        path = write(self.folder, "summary.json", '{"results": {"walls": [{"x": 1}]}}')
        summary = read_json(path)
        wall = lookup(summary, "results", "walls", 0)
        self.assertIsInstance(wall, Record)
        self.assertEqual((wall.source, wall.where), (path, ("results", "walls", 0)))
        self.assertEqual(summary, {"results": {"walls": [{"x": 1}]}})  # still plain data

    def test_an_absent_file(self):
        path = os.path.join(self.folder, "missing.json")
        self.assertIsNone(read_json(path))
        self.assertIsNone(read_table(path))
        with strict_mode():
            self.assertIsNone(read_json(path, optional=True))
            self.assertIsNone(read_table(path, optional=True))
            with self.assertRaises(MissingKey) as raised:
                read_json(path)
            self.assertIn("no file", str(raised.exception))
            with self.assertRaises(MissingKey):
                read_table(path)

    def test_table_comments_header_and_rows(self):
        path = write(self.folder, "bins.csv",
                     "# every bin: centre\n# second line\nx,y,T_particle\n1,1,0.9\n3,1,\n\n")
        table = Table(path)
        self.assertEqual(table.comments, ["every bin: centre", "second line"])
        self.assertEqual(table.header, ["x", "y", "T_particle"])
        self.assertEqual(len(table.rows), 2)  # the blank line is no row
        self.assertEqual(cell(table.rows[0], "T_particle"), "0.9")
        numbers = table.numbers("T_particle")
        self.assertEqual(numbers[0], 0.9)
        self.assertTrue(math.isnan(numbers[1]))  # an empty cell

    def test_table_columns_in_strict_mode(self):
        path = write(self.folder, "profiles.csv", "direction,T_particle\nx,1.0\n")
        table = Table(path)
        self.assertFalse(table.has("vx_particle"))
        self.assertEqual(cell(table.rows[0], "vx_particle"), "")
        with strict_mode():
            self.assertFalse(table.has("vx_particle"))  # a presence test: optional
            self.assertTrue(table.has("T_particle", optional=False))
            self.assertTrue(math.isnan(table.numbers("vx_particle", optional=True)[0]))
            for read in (lambda: table.has("T_nominal", optional=False),
                         lambda: table.numbers("T_nominal"),
                         lambda: cell(table.rows[0], "T_nominal")):
                with self.assertRaises(MissingKey) as raised:
                    read()
                self.assertEqual(str(raised.exception), f"{path}: no column 'T_nominal'")


class Grids(unittest.TestCase):
    def test_varied_keys_lie_between_exit_code_and_the_commands_columns(self):
        folder = tempfile.mkdtemp()
        path = write(folder, "sweep.csv", "point,status,reason,exit_code,Particle/Seed,"
                                          "Scene/Density,target_rayleigh,gravity,wall_seconds\n")
        self.assertEqual(varied_keys(Table(path), ("target_rayleigh", "gravity", "wall_seconds")),
                         ["Particle/Seed", "Scene/Density"])
        path = write(folder, "old.csv", "point,status,Particle/Seed\n")
        self.assertEqual(varied_keys(Table(path), ("wall_seconds",)), [])
        with strict_mode(), self.assertRaises(MissingKey):
            varied_keys(Table(path), ("wall_seconds",))

    def test_study_case_name(self):
        self.assertEqual(study_case_name({"base_parameters": {"Case name": "cavity"}}, "/x/y"),
                         "cavity")
        self.assertEqual(study_case_name({"base_parameters": {"Case name": ""},
                                          "case_file": "/c/heated_cavity_2d.prm"}, "/x/y"),
                         "heated_cavity_2d")
        self.assertEqual(study_case_name({}, "/x/sweep_dir/"), "sweep_dir")


if __name__ == "__main__":
    unittest.main()
