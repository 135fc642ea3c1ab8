"""Utilities/xserver.py: private X servers started side by side get displays of their own, a
server stops once the process that started it has gone, even when that process's output is
being read by a parent that waits for its end (the scripts that draw run so in test_readme), and
it does not reset when its last client leaves. make-tutorial-pictures.py refuses to start
without the programs it needs."""
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import unittest

UTILITIES = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "Utilities")
sys.path.insert(0, UTILITIES)
from xserver import ensure_display, reachable, start_private_display  # noqa: E402


def running(display):
    """Whether an X server listens on @p display's socket."""
    with socket.socket(socket.AF_UNIX) as s:
        try:
            s.connect("/tmp/.X11-unix/X" + display.lstrip(":"))
            return True
        except OSError:
            return False


def receive(connection, size):
    data = b""
    while len(data) < size:
        chunk = connection.recv(size - len(data))
        if not chunk:
            raise ConnectionError("the X server closed the connection")
        data += chunk
    return data


def intern_atom(display, name, only_if_exists):
    """The atom @p name on @p display (0 when it does not exist and @p only_if_exists), through
    the X protocol itself, as one client that then disconnects."""
    with socket.socket(socket.AF_UNIX) as connection:
        connection.settimeout(10)
        connection.connect("/tmp/.X11-unix/X" + display.lstrip(":"))
        connection.sendall(b"l\0" + struct.pack("<HHHH", 11, 0, 0, 0) + b"\0\0")
        head = receive(connection, 8)
        if head[0] != 1:
            raise ConnectionError("the X server refused the connection")
        receive(connection, 4 * struct.unpack("<H", head[6:8])[0])
        pad = b"\0" * (-len(name) % 4)
        connection.sendall(struct.pack("<BBHHH", 16, int(only_if_exists), 2 + (len(name) + len(pad)) // 4,
                                       len(name), 0) + name + pad)
        reply = receive(connection, 32)
        if reply[0] != 1:
            raise ConnectionError("InternAtom failed")
        return struct.unpack("<I", reply[8:12])[0]


class PrivateDisplayTest(unittest.TestCase):
    def test_no_reset_when_the_last_client_leaves(self):
        """An X server resets by default when its last client disconnects, and a client that
        connects meanwhile aborts (render-model.py did, 1-3 of every 4-6 runs). A reset forgets
        the atoms that clients made: one made by a client that has gone must still be there."""
        display = start_private_display()
        made = intern_atom(display, b"MSYNTH_NO_RESET_PROBE", False)
        self.assertNotEqual(made, 0)
        time.sleep(0.5)  # a reset would follow the disconnection at once
        self.assertEqual(intern_atom(display, b"MSYNTH_NO_RESET_PROBE", True), made)

    def test_tutorial_pictures_need_xwd(self):
        """Without xwd, make-tutorial-pictures.py says so in one line before it starts anything,
        and leaves no .ready file (it crashed after the first step's pipeline, leaving one)."""
        tools = tempfile.mkdtemp(prefix="msynth-no-xwd-")
        for tool in ("bash", "cat", "kill", "rm", "Xvfb", "paraview", "xwdtopnm", "pnmcrop", "pnmtopng"):
            if shutil.which(tool):
                os.symlink(shutil.which(tool), os.path.join(tools, tool))
        out = tempfile.mkdtemp(prefix="msynth-tutorial-")
        self.addCleanup(shutil.rmtree, out, True)
        script = os.path.join(UTILITIES, "make-tutorial-pictures.py")
        build = os.path.dirname(os.environ.get("MSYNTH_BIN", os.path.join(os.getcwd(), "bin")))
        try:
            done = subprocess.run([sys.executable, script, build, out], capture_output=True, text=True,
                                  timeout=300, env=dict(os.environ, PATH=tools))
        finally:
            shutil.rmtree(tools)
        self.assertNotEqual(done.returncode, 0)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        self.assertIn("xwd", done.stderr)
        self.assertIn("x11-apps", done.stderr)
        self.assertEqual([n for n in os.listdir(out) if n.startswith(".")], [])

    def test_side_by_side_and_gone_with_their_owner(self):
        child = ("import sys; sys.path.insert(0, %r); from xserver import start_private_display; "
                 "print(start_private_display(), start_private_display())" % UTILITIES)
        mine = start_private_display()
        start = time.time()
        done = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, timeout=120)
        self.assertLess(time.time() - start, 60, "the owner's output ended only with its servers")
        self.assertEqual(done.returncode, 0, done.stderr)
        first, second = done.stdout.split()
        self.assertEqual(len({first, second, mine}), 3)
        self.assertTrue(running(mine))
        for _ in range(100):
            if not running(first) and not running(second):
                break
            time.sleep(0.1)
        self.assertFalse(running(first) or running(second), "the servers outlived their owner")
        self.assertTrue(running(mine))

    def test_a_display_without_a_server_is_replaced(self):
        """DISPLAY pointing at no server (a closed session's) gets a private server instead."""
        os.environ["DISPLAY"] = ":%d" % (4000 + os.getpid() % 1000)
        self.assertFalse(reachable(os.environ["DISPLAY"]))
        private = ensure_display()
        self.assertTrue(reachable(private) and running(private))
        self.assertEqual(ensure_display(), private)
        for broken in ("", "nonsense", ":x", "localhost:1x"):
            self.assertFalse(reachable(broken), broken)


if __name__ == "__main__":
    unittest.main()
