"""Helpers shared by the Python tests of the command-line programs (<module>/tests/*_cli_test.py):
the program paths CTest passes, running a program, a temporary folder per test, and the check
that a program refused its input cleanly (exit code, one stderr line, no partial output).

A test finds this module through a sys.path entry computed from its own location:
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))), "core", "tests", "support"))
"""
import os
import subprocess
import sys
import tempfile
import unittest


def programs_from_argv(*defaults):
    """Takes one program path per default off the command line (CTest passes them first, before
    any unittest option), made absolute; a program not given stays its default name (on PATH)."""
    out = []
    for name in defaults:
        out.append(os.path.abspath(sys.argv.pop(1)) if len(sys.argv) > 1 else name)
    return out


def run(program, *args, env=None):
    """Runs a program with the arguments; returns the completed process (text stdout, stderr)."""
    return subprocess.run([program, *args], capture_output=True, text=True, env=env)


def generate(models, path, *args):
    """`models generate ARGS -o PATH`; returns PATH."""
    r = run(models, "generate", *args, "-o", path)
    if r.returncode != 0:
        raise AssertionError("models generate %s failed: %s" % (" ".join(args), r.stderr))
    return path


def temporary_folder(cleanup):
    """A new temporary folder, removed by the `cleanup` registration given (addCleanup,
    addClassCleanup)."""
    tmp = tempfile.TemporaryDirectory()
    cleanup(tmp.cleanup)
    return tmp.name


class CliTestCase(unittest.TestCase):
    """A test of one program, with a fresh temporary folder `self.dir` for every test."""

    #: True: one folder `dir` for all the tests of the class (for fixtures made once, in a
    #: setUpClass that calls this one first) instead of one per test.
    shared_folder = False
    #: Where set, every refusal's message starts with it (the program's name and ": ").
    message_prefix = None

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        if cls.shared_folder:
            cls.dir = temporary_folder(cls.addClassCleanup)

    def setUp(self):
        if not self.shared_folder:
            self.dir = temporary_folder(self.addCleanup)

    def path(self, name):
        return os.path.join(self.dir, name)

    def write(self, name, text):
        with open(self.path(name), "w") as f:
            f.write(text)
        return self.path(name)

    def is_leftover(self, name):
        """Whether a file left in self.dir by a refused run is a partial output."""
        return "partial" in name

    def assert_refused(self, r, code, message, outputs=()):
        """The run exited with `code` and one stderr line holding `message`, wrote none of
        `outputs` (paths) and left no partial file in self.dir."""
        self.assertNotIsInstance(outputs, str, "outputs: a list of paths")
        self.assertEqual(r.returncode, code, r.stderr)
        self.assertIn(message, r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        if self.message_prefix:
            self.assertTrue(r.stderr.startswith(self.message_prefix), r.stderr)
        for o in outputs:
            self.assertFalse(os.path.exists(o), o)
        self.assertFalse([f for f in os.listdir(self.dir) if self.is_leftover(f)])
