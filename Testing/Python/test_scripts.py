"""The scripts of Utilities/ a newcomer runs first: each answers --help with what it does and its
options (exit 0, nothing installed or built), refuses an unknown option (exit 2), and the
package sets of install-dependencies.sh are split by purpose: the main job's runtime set holds no
test tools, and the test set holds the runtime set, the test tools and the GUI's packages."""
import os
import subprocess
import unittest

UTILITIES = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                         "Utilities")

# script: the options its help must name
OPTIONS = {
    "run-example.sh": ["--out", "--seed", "--size", "--no-build", "--help", "--runtime", "--no-tests"],
    "make-readme-picture.sh": ["run-example.sh", "village.json", "--help"],
    "run-tests.sh": ["--no-sanitizers", "--no-fuzz", "--help", "--tests"],
    "build.sh": ["--no-tests", "--asan", "--help", "--runtime", "--tests"],
    "install-dependencies.sh": ["--runtime", "--gui", "--tests", "--all", "--list", "--help"],
    "fuzz.sh": ["SECONDS"],
}
TEST_ONLY = ["clang", "clang-format", "libclang-rt-14-dev", "libgtest-dev", "googletest",
             "libbenchmark-dev"]


def script(name, *args):
    return subprocess.run(["bash", os.path.join(UTILITIES, name), *args], capture_output=True,
                          text=True, timeout=60, cwd=UTILITIES)


def packages(*args):
    done = script("install-dependencies.sh", *args, "--list")
    assert done.returncode == 0, done.stderr
    return done.stdout.split()


class ScriptsTest(unittest.TestCase):
    def test_help(self):
        for name, options in OPTIONS.items():
            for flag in ("--help", "-h"):
                done = script(name, flag)
                self.assertEqual(done.returncode, 0, "%s %s: %s" % (name, flag, done.stderr))
                self.assertIn("Usage: Utilities/" + name if name != "fuzz.sh" else "Utilities/fuzz.sh",
                              done.stdout, name)
                for option in options:
                    self.assertIn(option, done.stdout, "%s --help does not mention %s" % (name, option))
                self.assertLess(len(done.stdout.splitlines()), 30, name + ": a few lines")
                self.assertNotIn("build.sh: built", done.stdout, name + " --help built something")

    def test_unknown_option(self):
        for name in ("run-example.sh", "run-tests.sh", "build.sh", "install-dependencies.sh",
                     "make-readme-picture.sh"):
            done = script(name, "--bogus")
            self.assertEqual(done.returncode, 2, name)
            self.assertIn("--bogus", done.stderr, name)
            self.assertIn("--help", done.stderr, name)

    def test_package_sets(self):
        runtime, gui, tests, everything = (packages(s) for s in ("--runtime", "--gui", "--tests", "--all"))
        self.assertEqual(packages(), everything, "the default is --all")
        for p in TEST_ONLY:
            self.assertNotIn(p, runtime, "the main job's runtime set holds the test tool " + p)
            self.assertNotIn(p, gui, "the GUI set holds the test tool " + p)
            self.assertIn(p, tests)
        for p in ("paraview-dev", "libopenvdb-dev", "libcgal-dev", "libcli11-dev", "cmake", "ninja-build",
                  "build-essential"):
            self.assertIn(p, runtime)
        for p in ("libqt5svg5", "xvfb", "x11-apps", "netpbm"):
            self.assertNotIn(p, runtime)
            self.assertIn(p, gui)
            self.assertIn(p, tests, "the GUI test needs " + p)
        self.assertLess(set(runtime), set(gui))
        self.assertLess(set(gui), set(tests))
        self.assertEqual(set(tests), set(everything))
        for listed in (runtime, gui, tests):
            self.assertEqual(len(listed), len(set(listed)), "a package listed twice")

    def test_main_job_builds_without_tests(self):
        """run-example.sh asks build.sh for --no-tests, which installs the runtime set only and
        configures without the tests and benchmarks (no GoogleTest, no Google Benchmark)."""
        with open(os.path.join(UTILITIES, "run-example.sh")) as f:
            self.assertIn('build.sh" --no-tests', f.read())
        with open(os.path.join(UTILITIES, "build.sh")) as f:
            text = f.read()
        self.assertIn("install-dependencies.sh\" --runtime", text)
        self.assertIn('-DMSYNTH_BUILD_TESTING="$tests" -DMSYNTH_BUILD_BENCHMARKS="$tests"', text)


if __name__ == "__main__":
    unittest.main()
