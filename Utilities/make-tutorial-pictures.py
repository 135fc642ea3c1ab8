#!/usr/bin/env python3
"""Screenshots of the real ParaView GUI for Documentation/paraview-tutorial.md.

Each step starts `paraview --script=...` on a private X server (Xvfb), with this file as the
script. The script loads the ModelSynth plugin and builds the step's pipeline through the same
proxies the GUI's menus create, then marks itself ready. Once the window has painted, the
screen is grabbed (xwd, then netpbm to PNG) and ParaView is closed.

    /usr/bin/python3 Utilities/make-tutorial-pictures.py [build] [Documentation/images/tutorial]

Needs Xvfb, xwd and netpbm (Debian: xvfb, x11-apps, netpbm), and libqt5svg5 for ParaView's
toolbar icons.
"""
import os
import shutil
import subprocess
import sys
import time

# ParaView runs a --script as text, without __file__: the launcher passes the checkout's root.
ROOT = os.environ.get("MSYNTH_TUTORIAL_ROOT") or os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))
STEPS = ("open-example", "synthesize", "catalog", "continuous")
SIZE = (1500, 940)


def gui_step(step):
    """Inside the GUI: the pipeline of one step, as a user clicks it together."""
    from paraview import simple as pv

    data = os.path.join(ROOT, "Data")
    pv.LoadPlugin(os.environ["MSYNTH_PLUGIN"], remote=False, ns=globals())
    view = pv.GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 1

    def show(source, port=0):
        return pv.Show(pv.OutputPort(source, port), view)

    reader = ModelSynthLabelGridReader(FileName=os.path.join(data, "Examples", "Village.vox"))  # noqa: F821
    pv.RenameSource("Village.vox", reader)
    if step == "open-example":
        show(reader)
        show(reader, 1)
        active = reader
    elif step in ("synthesize", "catalog"):
        model = ModelSynthDiscreteSynthesis(Input=reader, OutputSize=[32, 32, 5],  # noqa: F821
                                            BlockSize=[16, 16, 5], Seed=2,
                                            BoundaryLabels=[0, 0, 0, 0, 1, 0])
        for face in ("XMin", "XMax", "YMin", "YMax", "ZMin", "ZMax"):  # the panel's check boxes
            setattr(model, "Boundary" + face, 1)
        if step == "catalog":
            model.CatalogSnapshotsPerBlock = 4
        pv.RenameSource("Discrete Synthesis", model)
        show(model)
        show(model, 1)
        if step == "catalog":
            model.UpdatePipelineInformation()
            times = model.TimestepValues
            pv.GetAnimationScene().AnimationTime = times[len(times) // 2]
        active = model
    else:
        house = ModelSynthPolyhedralExampleReader(  # noqa: F821
            FileName=os.path.join(data, "Continuous", "house.obj"))
        pv.RenameSource("house.obj", house)
        planes = ModelSynthPlaneArrangement(Input=house, OutputSize=[24, 24, 10])  # noqa: F821
        labels = ModelSynthContinuousSynthesis(Input=house, Arrangement=planes, Seed=3,  # noqa: F821
                                               Grounded=1, Thickness="wall:z,wall:x:2+,wall:y:2+",
                                               Overhang="roof", Mirror=[1, 1, 0])
        mesh = ModelSynthArrangementMesh(Input=house, Arrangement=labels)  # noqa: F821
        for name, source in (("Plane Arrangement", planes), ("Continuous Synthesis", labels),
                             ("Arrangement Mesh", mesh)):
            pv.RenameSource(name, source)
        shown = show(mesh)
        pv.ColorBy(shown, ("CELLS", "InsideType"))
        active = labels
    view.CameraPosition = [-40, -55, 45] if step == "continuous" else [-12, -20, 18]
    view.CameraFocalPoint = [12, 12, 2] if step == "continuous" else [3, 3, 1]
    if step in ("synthesize", "catalog"):
        view.CameraPosition, view.CameraFocalPoint = [-25, -40, 40], [16, 16, 2]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    pv.SetActiveSource(active)
    pv.Render(view)
    with open(os.environ["MSYNTH_TUTORIAL_READY"], "w") as f:
        f.write(step)


# The programs this script runs, with the Debian packages that provide them.
TOOLS = (("paraview", "paraview"), ("Xvfb", "xvfb"), ("xwd", "x11-apps"), ("xwdtopnm", "netpbm"),
         ("pnmcrop", "netpbm"), ("pnmtopng", "netpbm"))


def check_tools():
    """Ends the script with one line naming the programs that are missing, before it starts any."""
    missing = [(tool, package) for tool, package in TOOLS if shutil.which(tool) is None]
    if missing:
        packages = sorted({package for _, package in missing})
        sys.exit("make-tutorial-pictures: %s not found (Debian: apt install %s)" % (
            ", ".join(tool for tool, _ in missing), " ".join(packages)))


def run(command, data=None):
    """The output of @p command; ends the script with one line when it fails."""
    done = subprocess.run(command, input=data, capture_output=True)
    if done.returncode != 0:
        reason = done.stderr.decode(errors="replace").strip().splitlines()
        sys.exit("make-tutorial-pictures: %s failed (exit %d)%s" % (
            command[0], done.returncode, ": " + reason[0] if reason else ""))
    return done.stdout


def grab(display, path):
    """The whole screen of @p display as a PNG."""
    pnm = run(["xwdtopnm"], run(["xwd", "-root", "-silent", "-display", display]))
    # The window does not fill the screen (no window manager): the black beyond it goes.
    pnm = run(["pnmcrop", "-black", "-right", "-bottom"], pnm)
    png = run(["pnmtopng", "-compression", "9"], pnm)
    with open(path, "wb") as f:
        f.write(png)


def main():
    check_tools()
    build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build"))
    out = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else
                          os.path.join(ROOT, "Documentation", "images", "tutorial"))
    os.makedirs(out, exist_ok=True)
    plugin = os.path.join(build, "lib", "paraview-5.11", "plugins", "ModelSynthPlugin",
                          "ModelSynthPlugin.so")
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from xserver import start_private_display
    display = start_private_display(*SIZE)
    # Fresh settings, the GUI as a new user sees it, without the welcome dialog (modal: it
    # would stop the script).
    home = os.path.join(out, ".paraview-home")
    os.makedirs(os.path.join(home, ".config", "ParaView"), exist_ok=True)
    with open(os.path.join(home, ".config", "ParaView", "ParaView5.11.0.ini"), "w") as f:
        f.write("[General]\nGeneralSettings.ShowWelcomeDialog=0\n")
    try:
        for step in STEPS:
            ready = os.path.join(out, ".ready")
            if os.path.exists(ready):
                os.remove(ready)
            env = dict(os.environ, DISPLAY=display, HOME=home, MSYNTH_PLUGIN=plugin, MSYNTH_TUTORIAL_ROOT=ROOT,
                       MSYNTH_TUTORIAL_STEP=step, MSYNTH_TUTORIAL_READY=ready)
            gui = subprocess.Popen(["paraview", "--script=" + os.path.abspath(__file__)], env=env,
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            try:
                for _ in range(240):
                    if os.path.exists(ready) or gui.poll() is not None:
                        break
                    time.sleep(0.5)
                if not os.path.exists(ready):
                    sys.exit("step %s: the GUI did not build the pipeline" % step)
                time.sleep(4)  # the window paints after the script returns
                grab(display, os.path.join(out, step + ".png"))
                print("wrote", os.path.join(out, step + ".png"))
            finally:
                gui.kill()
                gui.wait()
                if os.path.exists(ready):
                    os.remove(ready)
    finally:
        subprocess.run(["rm", "-rf", home])


if __name__ == "__main__" and not os.environ.get("MSYNTH_TUTORIAL_STEP"):
    main()
elif os.environ.get("MSYNTH_TUTORIAL_STEP"):
    gui_step(os.environ["MSYNTH_TUTORIAL_STEP"])
