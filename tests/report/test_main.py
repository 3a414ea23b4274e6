"""The command line (compare/report/__main__.py): which directory is which, exit codes, the
entry points (the folder as a script, as twinflow runs it, and python3 -m), strict mode."""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import report_path
from report.__main__ import kind_of

REPORT = os.path.join(report_path.SOURCE_DIR, "compare", "report")
FIXTURES = os.path.join(report_path.SOURCE_DIR, "tests", "study", "fixtures")


def touch(folder, *names):
    for name in names:
        path = os.path.join(folder, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        open(path, "w").close()


def run(*arguments, env=None):
    """python3 ARGUMENTS in the source directory; strict mode only when env asks for it."""
    environment = {k: v for k, v in os.environ.items() if k != "TWINFLOW_REPORT_STRICT"}
    environment.update(env or {})
    return subprocess.run([sys.executable, *arguments], capture_output=True, text=True,
                          env=environment, cwd=report_path.SOURCE_DIR)


class KindOf(report_path.FolderTestCase):
    def test_kinds(self):
        self.assertIsNone(kind_of(self.folder))
        touch(self.folder, "sweep.csv")
        self.assertIsNone(kind_of(self.folder))  # needs both files
        touch(self.folder, "sweep.json")
        self.assertEqual(kind_of(self.folder), "sweep")
        touch(self.folder, "compare/metrics.json")
        self.assertEqual(kind_of(self.folder), "run")  # a run first
        other = tempfile.mkdtemp(dir=self.folder)
        touch(other, "stability.csv", "stability.json")
        self.assertEqual(kind_of(other), "stability")


class CommandLine(report_path.FolderTestCase):
    def test_not_a_result_directory_exits_2(self):
        for arguments in ([self.folder], ["--strict", self.folder], [], ["a", "b"], ["--help"]):
            result = run(REPORT, *arguments)
            self.assertEqual(result.returncode, 2, arguments)
            self.assertEqual(len(result.stderr.splitlines()), 1, result.stderr)
        self.assertEqual(os.listdir(self.folder), [])

    def copy(self, fixture):
        directory = os.path.join(self.folder, fixture)
        shutil.copytree(os.path.join(FIXTURES, fixture), directory)
        return directory

    def test_every_entry_point_writes_the_same_report(self):
        directory = self.copy("stability_time_step")
        reports = []
        for entry in ([REPORT], [os.path.join(REPORT, "__main__.py")], ["-m", "compare.report"]):
            result = run(*entry, directory)
            self.assertEqual(result.returncode, 0, result.stderr)
            with open(os.path.join(directory, "report", "report.md"), encoding="utf-8") as f:
                reports.append(f.read())
        self.assertEqual(reports[1:], reports[:1] * 2)
        self.assertIn("# Stability map:", reports[0])

    def test_strict_mode_exits_3_and_writes_nothing(self):
        # The fixture's metrics.json predates nusselt_stderr_from_coefficients.
        directory = self.copy("run_2d")
        for arguments, env in ((["--strict", directory], None),
                               ([directory], {"TWINFLOW_REPORT_STRICT": "1"})):
            result = run(REPORT, *arguments, env=env)
            self.assertEqual(result.returncode, 3, result.stderr)
            self.assertEqual(result.stderr.strip(), "report: strict: " + os.path.join(
                directory, "compare", "metrics.json") + ": no key "
                "'twins/nominal/nusselt_stderr_from_coefficients'")
            self.assertEqual(sorted(os.listdir(directory)), ["compare", "continuum", "particle"])
        result = run(REPORT, directory)  # without strict mode: written
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(os.path.isfile(os.path.join(directory, "report", "report.md")))


if __name__ == "__main__":
    unittest.main()
