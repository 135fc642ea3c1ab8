"""Testing/Benchmarks/perf-tables.py, which regenerates the whole-command tables of
Documentation/performance.md: two of its subcommands run at --small sizes and print their
Markdown tables (a row per command, every run finished), and the document and the script name
the same subcommands (each `perf-tables.py NAME` of the document is one of the script's, and each
of the script's is used by the document)."""
import os
import re
import subprocess
import sys
import unittest

from msynth_testing import BIN, fresh_folder

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "Testing", "Benchmarks", "perf-tables.py")


def subcommands():
    """The script's subcommands, from its argparse choices (its usage line)."""
    usage = subprocess.run([sys.executable, SCRIPT, "--help"], capture_output=True, text=True,
                           check=True).stdout
    names = re.search(r"\{([a-z,-]+)\}", usage).group(1).split(",")
    return set(names) - {"all"}


class PerfTablesTest(unittest.TestCase):
    def run_tables(self, name):
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("the tables are timed in the Release build")
        done = subprocess.run([sys.executable, SCRIPT, name, "--small", "--msynth",
                               os.path.join(BIN, "msynth"), "--keep",
                               fresh_folder("perf-tables-" + name)],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        rows = [l for l in done.stdout.splitlines() if l.startswith("| ")]
        self.assertIn("<!-- perf-tables.py %s" % name, done.stdout)
        return rows[1:]  # without the header

    def test_whole_runs(self):
        rows = self.run_tables("whole-runs")
        self.assertEqual(len(rows), 9, "\n".join(rows))
        for row in rows:
            cells = [c.strip() for c in row.strip("|").split("|")]
            self.assertRegex(cells[2], r"^\d+\.\d+$", row)  # wall seconds
            self.assertNotEqual(cells[5], "–", row)  # statistics.json's Seconds

    def test_connected(self):
        rows = self.run_tables("connected")
        self.assertEqual(len(rows), 3, "\n".join(rows))
        for row in rows:
            cells = [c.strip() for c in row.strip("|").split("|")]
            self.assertEqual(cells[2], "1", row)  # one network, and msynth check agrees

    def test_the_document_names_the_subcommands(self):
        with open(os.path.join(ROOT, "Documentation", "performance.md")) as f:
            text = f.read()
        used = set(re.findall(r"perf-tables\.py\s+([a-z-]+)", text)) - {"all"}
        self.assertEqual(used, subcommands())


if __name__ == "__main__":
    unittest.main()
