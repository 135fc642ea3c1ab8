"""Times a world computed in pieces, one per MPI rank, through the streaming pipeline
(ComputeRequestedExtent: each rank computes its piece from the blocks it depends on, with no
exchange), against the same run on one rank.

    mpirun -np 2 pvbatch --mpi Utilities/mpi-world-timing.py \\
        build/lib/paraview-5.11/plugins/ModelSynthPlugin/ModelSynthPlugin.so [N]

Figures in Documentation/performance.md ("MPI")."""
import os
import sys
import time

from paraview import servermanager
import paraview.simple as ps

ps.LoadPlugin(sys.argv[1], remote=True, ns=globals())
n = int(sys.argv[2]) if len(sys.argv) > 2 else 2048
here = os.path.dirname(os.path.abspath(__file__))
reader = ModelSynthLabelGridReader(FileName=os.path.join(here, "..", "Data", "Examples", "Village.vti"))  # noqa: F821
reader.UpdatePipeline()
synthesis = ModelSynthDiscreteSynthesis(Input=reader, OutputSize=[n, n, 5], BlockSize=[32, 32, 5],  # noqa: F821
                                        Seed=4, NumberOfThreads=1, ComputeRequestedExtent=1,
                                        GenerateGeometry=0)
start = time.time()
synthesis.UpdatePipeline()
seconds = time.time() - start
info = synthesis.GetDataInformation()
print("ranks=%d world=%dx%dx5 seconds=%.2f points=%d" % (
    servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions(), n, n, seconds,
    info.GetNumberOfPoints()), flush=True)
