"""Utilities/xserver.py: private X servers started side by side get displays of their own, and a
server stops once the process that started it has gone, even when that process's output is
being read by a parent that waits for its end (the scripts that draw run so in test_readme)."""
import os
import socket
import subprocess
import sys
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


class PrivateDisplayTest(unittest.TestCase):
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
