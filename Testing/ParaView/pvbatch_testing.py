"""What the serial pvbatch scripts share: the test data paths from ctest's environment, the
plugin loaded into the caller's namespace, and a check that fails the script with a message."""
import os
import sys

DATA = os.environ["MSYNTH_DATA"]
TMP = os.environ["MSYNTH_TMP"]


def load_plugin(namespace):
    """Loads the build's ModelSynth plugin; its proxies appear in `namespace` (globals())."""
    from paraview.simple import LoadPlugin
    LoadPlugin(os.environ["MSYNTH_PLUGIN"], remote=False, ns=namespace)


def check(condition, message):
    if not condition:
        print("FAILED: " + message)
        sys.exit(1)
