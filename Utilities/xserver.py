"""A private X server for scripts that draw. ParaView's Debian build renders through GLX only, so
even an offscreen picture needs an X server; where there is none, these functions start Xvfb.

Xvfb chooses a free display itself (-displayfd): it takes the first number whose socket it can
bind, so any number of these servers run side by side, with each other and with other X users.
(`xvfb-run -a` chooses by the lock files in /tmp alone, and two of them started together, or one
beside a server whose lock file it cannot see, can share a number: a client then connects to the
wrong server and aborts.) The server lives as long as the process that started it: a watcher
stops it once that process has gone, however it ended, and holds none of its output pipes."""
import os
import select
import socket
import subprocess

# Started with bash: Xvfb in the background; the shell lets go of the display pipe (so that the
# reader sees its end if Xvfb fails) and waits for the end of the life pipe, whose other end only
# the owner holds: when the owner has gone (or is a zombie), the server is stopped. -noreset: by
# default an X server resets when its last client disconnects, and a client that connects during
# the reset aborts ("bad X server connection"); a script that draws and closes windows in turn,
# as render-model.py does, met that in 1-3 of every 4-6 runs.
WATCHER = ('Xvfb -displayfd {display} -screen 0 {w}x{h}x24 -nolisten tcp -noreset >/dev/null 2>&1 & x=$!; '
           'exec {display}>&-; cat <&{life} >/dev/null; kill $x 2>/dev/null; wait $x')

_lives = []  # the write ends of the life pipes (open until this process ends) and the watchers


def start_private_display(width=1600, height=1200, timeout=60):
    """Starts Xvfb on a free display for as long as this process lives; returns ":N"."""
    read, write = os.pipe()
    life_read, life_write = os.pipe()
    try:
        watcher = subprocess.Popen(["bash", "-c", WATCHER.format(display=write, life=life_read, w=width, h=height)],
                         pass_fds=(write, life_read), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL, start_new_session=True)
    finally:
        os.close(write)
        os.close(life_read)
    _lives.append((life_write, watcher))
    number = b""
    try:
        while not number.endswith(b"\n"):
            if not select.select([read], [], [], timeout)[0]:
                raise SystemExit("Xvfb did not start within %d s" % timeout)
            chunk = os.read(read, 16)
            if not chunk:
                raise SystemExit("Xvfb could not start (is it installed? Debian: apt install xvfb)")
            number += chunk
    finally:
        os.close(read)
    return ":" + number.decode().strip()


def reachable(display):
    """Whether an X server answers at @p display ("[host]:N[.S]"): its local socket, or TCP port
    6000 + N on a host (as ssh's X forwarding gives)."""
    host, _, number = display.rpartition(":")
    number = number.split(".")[0]
    if not number.isdigit():
        return False
    if host in ("", "unix"):
        family, addresses = socket.AF_UNIX, ["\0/tmp/.X11-unix/X" + number, "/tmp/.X11-unix/X" + number]
    else:
        family, addresses = socket.AF_INET, [(host, 6000 + int(number))]
    for address in addresses:
        with socket.socket(family) as s:
            s.settimeout(5)
            try:
                s.connect(address)
                return True
            except OSError:
                pass
    return False


def ensure_display(width=1600, height=1200):
    """Leaves DISPLAY as it is when an X server answers there; otherwise starts a private Xvfb and
    points DISPLAY at it (before the first window is made, it is what VTK connects to)."""
    if not reachable(os.environ.get("DISPLAY", "")):
        os.environ["DISPLAY"] = start_private_display(width, height)
    return os.environ["DISPLAY"]
