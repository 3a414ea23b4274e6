"""Imported first by every test module: compare/ on sys.path, so that `report` is the package
compare/report/, and matplotlib on its file backend (as __main__.py sets it)."""

import os
import sys

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
COMPARE_DIR = os.path.join(SOURCE_DIR, "compare")
if COMPARE_DIR not in sys.path:
    sys.path.insert(0, COMPARE_DIR)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
