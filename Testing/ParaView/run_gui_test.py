"""Starts the ParaView GUI on a private Xvfb with gui_plugin.py and checks what the script reported."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "Utilities"))
from xserver import start_private_display  # noqa: E402

paraview, script = sys.argv[1:3]
report = os.path.join(os.environ["MSYNTH_TMP"], "gui-report.txt")
if os.path.exists(report):
    os.remove(report)
env = dict(os.environ, DISPLAY=start_private_display(1280, 1024), MSYNTH_GUI_REPORT=report,
           MSYNTH_GUI_BASELINE=os.path.join(os.path.dirname(os.path.abspath(__file__)), "Baseline", "gui-houses.png"))
try:
    gui = subprocess.run([paraview, "--script=" + script], env=env, timeout=240, capture_output=True,
                         text=True)
except subprocess.TimeoutExpired:
    sys.exit("the ParaView GUI did not finish the script within 240 s")
if not os.path.exists(report):
    sys.exit("the GUI script wrote no report (exit code %d):\n%s\n...\n%s" % (
        gui.returncode, gui.stderr[:3000], gui.stderr[-2000:]))
text = open(report).read()
print(text)
sys.exit(0 if text == "OK labels=4 continuous=28 model=valid frames=6 reseeded=True categorical=True picture=matches tutorial=ok" else 1)
