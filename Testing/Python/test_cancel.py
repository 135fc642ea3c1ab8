"""One cancel path for every synthesis filter (issue 25): a filter whose run is aborted through
VTK's AbortExecute (what ParaView's cancel and the Python progress observers set) fails its
request quietly, with an empty output and no error message; the next update, not aborted,
computes the model again (the cancelled run is not cached)."""
import unittest

from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import modelsynth
from msynth_testing import ErrorObserver, data


def discrete():
    reader = modelsynth.vtkMSLabelGridReader()
    reader.SetFileName(data("Examples/Village.vti"))
    s = modelsynth.vtkMSDiscreteSynthesis()
    s.SetInputConnection(reader.GetOutputPort())
    s.SetOutputSize(40, 40, 5)
    s.SetBlockSize(10, 10, 5)
    return s


def pattern():
    reader = vtkXMLImageDataReader()
    reader.SetFileName(data("Patterns/facade-rectangular.vti"))
    reader.Update()
    s = modelsynth.vtkMSPatternSynthesis()
    s.AddExemplarData(reader.GetOutput())
    s.SetOutputSize(16, 12, 1)
    s.SetSamples(2)
    return s


def continuous():
    reader = modelsynth.vtkMSPolyhedralExampleReader()
    reader.SetFileName(data("Continuous/cube.obj"))
    arrangement = modelsynth.vtkMSPlaneArrangement()
    arrangement.SetInputConnection(reader.GetOutputPort())
    arrangement.SetOutputSize(6, 6, 4)
    s = modelsynth.vtkMSContinuousSynthesis()
    s.SetInputConnection(0, reader.GetOutputPort())
    s.SetArrangementConnection(arrangement.GetOutputPort())
    s.SetBlockSize(2)
    s._keep = (reader, arrangement)
    return s


class CancelTest(unittest.TestCase):
    def test_every_filter_cancels_alike(self):
        for name, make in (("discrete", discrete), ("pattern", pattern), ("continuous", continuous)):
            with self.subTest(filter=name):
                s = make()
                errors = ErrorObserver(s)
                tag = s.AddObserver("ProgressEvent", lambda obj, event: obj.SetAbortExecute(1))
                s.Update()
                self.assertEqual(errors.text(), "", name)
                self.assertEqual(s.GetOutput().GetNumberOfPoints(), 0, name)
                s.RemoveObserver(tag)
                s.SetAbortExecute(0)
                s.Modified()
                s.Update()
                self.assertEqual(errors.text(), "", name)
                self.assertGreater(s.GetOutput().GetNumberOfPoints(), 0, name)


if __name__ == "__main__":
    unittest.main()
