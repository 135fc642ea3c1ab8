"""Examples made infallible (issue 28 §4, D§3.3.8): `msynth analyze --infallible` finds a refinement
E_I of the dissertation's two fallible examples (Figs. 3.5(a), 3.6(a)) and writes it with f;
`synthesize --via-infallible` makes whole models on E_I over 20 seeds each, never failing, and
each model passes `msynth check` against the ORIGINAL example (and a numpy recount of its
pairs). The filter's ViaInfallible property from Python; bad uses give one line."""
import os
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import modelsynth
from msynth_testing import data, fresh_folder, labels_zyx, violations
from msynth_testing import read_label_grid as read
from msynth_testing import run_msynth as msynth

FIG_35A = data("Examples/Fallible-Fig3.5a.vti")
FIG_36A = data("Examples/Fallible-Fig3.6a.vti")


class InfallibleTest(unittest.TestCase):
    def test_analyze_converts_both_and_writes_e_i_with_f(self):
        for example, renamed in ((FIG_35A, "9->0"), (FIG_36A, "7->2")):
            # (in a folder not made yet, as output/infallible/ in a fresh checkout: made, as --out)
            out = os.path.join(fresh_folder("infallible-analyze"), "infallible", "EI.vti")
            done = msynth("analyze", example, "--infallible", "--write-infallible", out)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertIn("step | split | labels | Algorithm 3.6 | Eq. 3.13 | why", done.stdout)
            self.assertIn("0 | none (the example itself) |", done.stdout)
            self.assertIn("infallible: refined by splitting", done.stdout)
            self.assertIn("f: " + renamed + " ", done.stdout)
            # E_I reads back as a label grid; f(E_I) = E (Eq. 3.12 / 3.14).
            xml = vtkXMLImageDataReader()
            xml.SetFileName(out)
            xml.Update()
            refined = xml.GetOutput()
            pairs = vtk_to_numpy(refined.GetFieldData().GetArray("InfallibleLabelMap"))
            f = {int(a): int(b) for a, b in pairs}
            e_i = labels_zyx(refined)
            e = labels_zyx(read(example))
            self.assertEqual(np.vectorize(f.get)(e_i).tolist(), e.tolist())
            self.assertGreater(len(np.unique(e_i)), len(np.unique(e)))
            # A model of E_I passes the check against E_I itself.
            folder = fresh_folder("infallible-ei")
            run = msynth("synthesize", out, "--size", "20", "16", "1", "--out", folder,
                         "--outputs", "labels")
            self.assertEqual(run.returncode, 0, run.stderr)

    def test_whole_runs_never_fail_and_pass_the_original_check(self):
        for example in (FIG_35A, FIG_36A):
            e = labels_zyx(read(example))
            made = set()
            for seed in range(20):
                folder = fresh_folder("infallible-run")
                size = [str(16 + seed % 7), str(12 + seed % 5), "1"]
                done = msynth("synthesize", example, "--size", *size, "--via-infallible",
                              "--seed", str(seed), "--out", folder, "--outputs", "labels")
                self.assertEqual(done.returncode, 0, done.stderr)
                self.assertIn("via an infallible refinement", done.stdout)
                self.assertIn(", 1 block (0 failed)", done.stdout)
                model = os.path.join(folder, "labels.vti")
                check = msynth("check", example, model)
                self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
                self.assertIn("consistent", check.stdout)
                labels = labels_zyx(read(model))
                self.assertEqual(violations(e, labels), [])
                self.assertTrue(set(np.unique(labels).tolist()) <= set(np.unique(e).tolist()))
                made.update(np.unique(labels).tolist())
            self.assertIn(2, made, example)  # structures are made, not only empty space

    def test_the_filter_property(self):
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(FIG_35A)
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        synthesis.SetInputConnection(reader.GetOutputPort())
        synthesis.SetOutputSize(24, 18, 1)
        synthesis.SetViaInfallible(True)
        synthesis.SetSeed(5)
        synthesis.Update()
        model = synthesis.GetOutput()
        message = model.GetFieldData().GetAbstractArray("Message").GetValue(0)
        self.assertIn("label 0 by -x=2", message)
        labels = labels_zyx(model)
        self.assertEqual(violations(labels_zyx(reader.GetOutput()), labels), [])
        self.assertLessEqual(int(labels.max()), 8)

    def test_bad_uses_give_one_line(self):
        folder = fresh_folder("infallible-bad")
        cases = [
            ("synthesize", FIG_35A, "--size", "20", "20", "1", "--via-infallible", "--block",
             "8", "8", "1", "--out", folder),
            ("synthesize", FIG_35A, "--size", "20", "20", "1", "--via-infallible", "--order",
             "random", "--out", folder),
            ("synthesize", data("Tilesets/Lines.xml"), "--size", "8", "8", "1",
             "--via-infallible", "--out", folder),
            ("analyze", data("Tilesets/Lines.xml"), "--infallible"),
            ("analyze", FIG_35A, "--write-infallible", os.path.join(folder, "x.vti")),
        ]
        for args in cases:
            done = msynth(*args)
            self.assertNotEqual(done.returncode, 0, args)
            self.assertEqual(len(done.stderr.strip().splitlines()), 1, (args, done.stderr))
            self.assertNotIn("Traceback", done.stderr)
        self.assertFalse(os.path.exists(os.path.join(folder, "labels.vti")))

    def test_an_example_not_converted_says_so(self):
        done = msynth("analyze", data("Examples/Houses.vox"), "--infallible")
        self.assertEqual(done.returncode, 3, done.stderr)
        self.assertIn("not converted: no refinement among the", done.stdout)
        folder = fresh_folder("infallible-houses")
        run = msynth("synthesize", data("Examples/Houses.vox"), "--size", "12", "12", "6",
                     "--via-infallible", "--out", folder)
        self.assertEqual(run.returncode, 1)
        self.assertIn("no infallible refinement", run.stderr)


if __name__ == "__main__":
    unittest.main()
