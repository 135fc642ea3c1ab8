"""Starts the ParaView GUI under Xvfb with gui_plugin.py and checks what the script reported."""
import os
import subprocess
import sys

xvfb_run, paraview, script = sys.argv[1:4]
report = os.path.join(os.environ["MSYNTH_TMP"], "gui-report.txt")
if os.path.exists(report):
    os.remove(report)
env = dict(os.environ, MSYNTH_GUI_REPORT=report,
           MSYNTH_GUI_BASELINE=os.path.join(os.path.dirname(os.path.abspath(__file__)), "Baseline", "gui-houses.png"))
try:
    subprocess.run([xvfb_run, "-a", paraview, "--script=" + script], env=env, timeout=240,
                   capture_output=True)
except subprocess.TimeoutExpired:
    sys.exit("the ParaView GUI did not finish the script within 240 s")
if not os.path.exists(report):
    sys.exit("the GUI script wrote no report")
text = open(report).read()
print(text)
sys.exit(0 if text == "OK labels=4 continuous=28 model=valid frames=6 reseeded=True picture=matches" else 1)
