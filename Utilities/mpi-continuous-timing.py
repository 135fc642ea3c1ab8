"""Times continuous synthesis of the house with its blocks on one process or spread over MPI
ranks (one thread per rank), the solver alone: the arrangement is built before the clock starts.

    mpirun -np 2 pvbatch --mpi Utilities/mpi-continuous-timing.py \\
        build/lib/paraview-5.11/plugins/ModelSynthPlugin/ModelSynthPlugin.so [SIZE]

SIZE (default 48) gives a SIZE x SIZE x 10 house. Run it on one process too (plain pvbatch) for
the one-rank time. Figures in Documentation/performance.md ("MPI")."""
import os
import sys
import time

import paraview.simple as ps
from paraview import servermanager
from paraview.simple import Delete  # noqa: F401

ps.LoadPlugin(sys.argv[1], remote=True, ns=globals())
size = int(sys.argv[2]) if len(sys.argv) > 2 else 48
here = os.path.dirname(os.path.abspath(__file__))
house = ModelSynthPolyhedralExampleReader(  # noqa: F821
    FileName=os.path.join(here, "..", "Data", "Continuous", "house.obj"))
arrangement = ModelSynthPlaneArrangement(Input=house, OutputSize=[size, size, 10])  # noqa: F821
arrangement.UpdatePipeline()
labels = []
for distribute in (0, 1, 0, 1):
    solver = ModelSynthContinuousSynthesis(Input=house, Arrangement=arrangement, Seed=5,  # noqa: F821
                                           BlockSize=4, NumberOfThreads=1,
                                           DistributeBlocks=distribute)
    start = time.time()
    solver.UpdatePipeline()
    seconds = time.time() - start
    model = servermanager.Fetch(solver)
    fields = model.GetFieldData()
    label = model.GetPointData().GetArray("Label")
    labels.append([label.GetValue(i) for i in range(label.GetNumberOfTuples())])
    print("DistributeBlocks=%d: %.2f s (solver %.2f s, %d processes, %d blocks in %d phases)"
          % (distribute, seconds, fields.GetArray("Seconds").GetValue(0),
             fields.GetArray("Processes").GetValue(0), fields.GetArray("Blocks").GetValue(0),
             fields.GetArray("Phases").GetValue(0)), flush=True)
    Delete(solver)
print("the same labels in every run:", all(x == labels[0] for x in labels))
