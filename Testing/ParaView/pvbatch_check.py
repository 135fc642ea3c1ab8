"""pvbatch: the plugin's ModelSynth Check Model on a synthesized model (reader -> discrete
synthesis -> check with the reader as example): verdict 1 and no violations; the same filter on
a model that is not the example's (the checkerboard against the village) gives verdict 0 with
its violations counted and listed."""
import os

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403

from pvbatch_testing import DATA, check, load_plugin

load_plugin(globals())


def value(data, name):
    a = data.GetFieldData().GetAbstractArray(name)
    check(a is not None, "field data " + name)
    return a.GetVariantValue(0).ToDouble() if a.IsNumeric() else a.GetValue(0)


village = ModelSynthLabelGridReader(FileName=os.path.join(DATA, "Examples", "Village.vti"))
synthesis = ModelSynthDiscreteSynthesis(Input=village, OutputSize=[16, 16, 5], BlockSize=[8, 8, 5], Seed=5)
checked = ModelSynthCheckModel(Input=synthesis, Examples=[village])
checked.UpdatePipeline()
model = servermanager.Fetch(checked)
check(model.GetDimensions() == (16, 16, 5), "the model passes through: %s" % (model.GetDimensions(),))
check(value(model, "Valid") == 1, "a synthesized model is valid")
check(value(model, "Violations") == 0, "no violations")
check(value(model, "PairsChecked") == 15 * 16 * 5 * 2 + 16 * 16 * 4, "every adjacent pair checked")

checkerboard = ModelSynthLabelGridReader(FileName=os.path.join(DATA, "Examples", "Checkerboard.vti"))
wrong = ModelSynthCheckModel(Input=checkerboard, Examples=[village], MaximumReported=3)
wrong.UpdatePipeline()
verdict = servermanager.Fetch(wrong)
check(value(verdict, "Valid") == 0, "the checkerboard is not a village")
check(value(verdict, "Violations") > 3, "violations counted: %g" % value(verdict, "Violations"))
check(verdict.GetFieldData().GetAbstractArray("Problems").GetNumberOfValues() == 3, "three listed")
check(verdict.GetFieldData().GetArray("ViolationSites").GetNumberOfComponents() == 3, "sites x, y, z")
print("pvbatch check model: ok")
