"""The build's package imports from /usr/bin/python3 against ParaView's VTK."""
import unittest

import vtkmodules
import modelsynth


class ImportTest(unittest.TestCase):
    def test_classes_are_exposed(self):
        for name in ("vtkMSLabelGridReader", "vtkMSTransitionTables", "vtkMSOpenVDBWriter",
                     "vtkMSOpenVDBReader", "vtkMSDiscreteSynthesis", "vtkMSLabelGeometry", "vtkMSTileImage"):
            self.assertTrue(hasattr(modelsynth, name), name)
            obj = getattr(modelsynth, name)()
            self.assertEqual(obj.GetClassName(), name)
        self.assertFalse(hasattr(modelsynth, "vtkMSEngineBridge"))  # not wrapped on purpose

    def test_uses_paraviews_vtk(self):
        # ParaView's VTK (9.2) lives in dist-packages next to paraview; Debian's VTK 9.1 would not.
        self.assertIn("dist-packages", vtkmodules.__file__)
        from vtkmodules.vtkCommonCore import vtkVersion
        self.assertTrue(vtkVersion.GetVTKVersion().startswith("9.2"))


if __name__ == "__main__":
    unittest.main()
