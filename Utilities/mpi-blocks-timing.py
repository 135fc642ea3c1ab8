"""Times discrete synthesis with and without blocks spread over MPI ranks.

    PYTHONPATH=build/lib/python3.11/site-packages mpirun -np 2 pvbatch --mpi \\
        Utilities/mpi-blocks-timing.py build/lib/paraview-5.11/plugins/ModelSynthPlugin/ModelSynthPlugin.so

Figures in Documentation/performance.md ("MPI")."""
import os
import sys
import time

import paraview.simple as ps
from paraview.simple import Delete  # noqa: F401

ps.LoadPlugin(sys.argv[1], remote=True, ns=globals())
here = os.path.dirname(os.path.abspath(__file__))
reader = ModelSynthLabelGridReader(FileName=os.path.join(here, "..", "Data", "Examples", "Village.vti"))  # noqa: F821
for distribute in (0, 1, 0, 1):
    synthesis = ModelSynthDiscreteSynthesis(Input=reader, OutputSize=[700, 700, 5],  # noqa: F821
                                            BlockSize=[16, 16, 5], Seed=4, NumberOfThreads=1,
                                            DistributeBlocks=distribute)
    start = time.time()
    synthesis.UpdatePipeline()
    print("DistributeBlocks=%d: %.2f s" % (distribute, time.time() - start), flush=True)
    Delete(synthesis)
