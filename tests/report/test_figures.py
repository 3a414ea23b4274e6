"""report.figures: the plot axis of a sweep or stability key, arrow keys, bin edges."""

import math
import unittest

import report_path  # noqa: F401  (compare/ on sys.path, Agg backend)
from report.figures import Axis, edges, nice_arrow


class AxisOfAColumn(unittest.TestCase):
    def test_numbers_spanning_a_decade_are_logarithmic(self):
        axis = Axis("Particle/Time step", ["0.10", "0.01", "0.02", "0.01", ""])
        self.assertTrue(axis.numeric)
        self.assertTrue(axis.log)  # 0.1 >= 10 x 0.01
        self.assertEqual(axis.values, [0.01, 0.02, 0.1])  # sorted, unique, blanks left out
        self.assertEqual(axis.texts, ["0.01", "0.02", "0.10"])  # as the user wrote them
        self.assertEqual(axis.position("0.02"), 0.02)

    def test_numbers_within_a_decade_or_not_positive_are_linear(self):
        self.assertFalse(Axis("k", ["1", "2", "9"]).log)
        self.assertFalse(Axis("k", ["-1", "100"]).log)
        self.assertFalse(Axis("k", ["0", "100"]).log)

    def test_words_are_categories_in_first_seen_order(self):
        axis = Axis("Particle/Integrator", ["shardlow", "velocity-verlet", "shardlow", ""])
        self.assertFalse(axis.numeric)
        self.assertFalse(axis.log)
        self.assertEqual(axis.categories, ["shardlow", "velocity-verlet"])
        self.assertEqual(axis.position("velocity-verlet"), 1)
        self.assertTrue(math.isnan(axis.position("other")))

    def test_a_mixed_column_is_categorical(self):
        self.assertFalse(Axis("k", ["1", "two"]).numeric)

    def test_apply_sets_scale_and_ticks(self):
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots()
        Axis("dt", ["0.01", "0.1"]).apply(ax, "x", ticks_at_values=True)
        self.assertEqual(ax.get_xscale(), "log")
        self.assertEqual(list(ax.get_xticks()), [0.01, 0.1])
        self.assertEqual([t.get_text() for t in ax.get_xticklabels()], ["0.01", "0.1"])
        Axis("scheme", ["a", "b", "c"]).apply(ax, "y")
        self.assertEqual(ax.get_ylim(), (-0.5, 2.5))
        self.assertEqual([t.get_text() for t in ax.get_yticklabels()], ["a", "b", "c"])
        plt.close(fig)


class Helpers(unittest.TestCase):
    def test_nice_arrow_rounds_to_1_2_5(self):
        self.assertEqual(nice_arrow(0.013), 0.01)
        self.assertEqual(nice_arrow(0.026), 0.02)
        self.assertEqual(nice_arrow(0.06), 0.05)
        self.assertEqual(nice_arrow(0.09), 0.1)
        self.assertEqual(nice_arrow(math.nan), 1.0)
        self.assertEqual(nice_arrow(0), 1.0)

    def test_edges_of_uniform_bins(self):
        import numpy as np
        self.assertEqual(list(edges(np.array([1.0, 3.0, 5.0]))), [0.0, 2.0, 4.0, 6.0])
        self.assertEqual(list(edges(np.array([2.5]))), [0.0, 5.0])


if __name__ == "__main__":
    unittest.main()
