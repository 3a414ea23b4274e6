"""Imported first by every test module: compare/ on sys.path, so that `report` is the package
compare/report/, and matplotlib on its file backend (as __main__.py sets it); and what the tests
share: a test case with its own temporary folder."""

import os
import shutil
import sys
import tempfile
import unittest

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
COMPARE_DIR = os.path.join(SOURCE_DIR, "compare")
if COMPARE_DIR not in sys.path:
    sys.path.insert(0, COMPARE_DIR)

import matplotlib  # noqa: E402

matplotlib.use("Agg")


class FolderTestCase(unittest.TestCase):
    """A test case with a fresh temporary folder, self.folder, removed after each test."""

    def setUp(self):
        self.folder = tempfile.mkdtemp()

    def tearDown(self):
        shutil.rmtree(self.folder)
