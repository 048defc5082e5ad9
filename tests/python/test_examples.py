"""The examples in clients/python/examples, run as a user runs them (a separate Python process with --target) against
one holotraced on a temporary socket; their output files are checked, not just their exit codes."""

import os
import re
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from daemon import EXAMPLES, Daemon
from holotrace_client import read_png


class ExampleTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.daemon = Daemon().__enter__()
        cls.work = tempfile.TemporaryDirectory(prefix="ht-py-examples-")

    @classmethod
    def tearDownClass(cls):
        cls.work.cleanup()
        cls.daemon.__exit__(None, None, None)

    def run_example(self, script, *args, expect=0):
        result = subprocess.run([sys.executable, os.path.join(EXAMPLES, script), "--target", self.daemon.target,
                                 *args], capture_output=True, text=True, timeout=240, cwd=self.work.name)
        self.assertEqual(result.returncode, expect, f"{script} {args}:\n{result.stdout}\n{result.stderr}")
        return result

    def test_turntable_capture(self):
        # The 3x2 capture grid (its views form a quilt), three steps of 120 degrees.
        out = self.run_example("turntable_capture.py", "--display", "rig", "--steps", "3", "--name", "tt").stdout
        names = [f"tt_s{step:03d}_f0000_qs3x2a1.5.png" for step in range(3)]
        quilts = []
        for name in names:
            self.assertIn(name, out)
            quilts.append(read_png(os.path.join(self.daemon.output_root, name)))
            self.assertEqual(quilts[-1].shape[:2], (32, 72))
            self.assertTrue(os.path.exists(os.path.join(self.daemon.output_root, name[:-4] + ".json")))
        for a, b in ((0, 1), (1, 2), (0, 2)):
            self.assertFalse(np.array_equal(quilts[a], quilts[b]), f"steps {a} and {b} look the same")
        # A single-view display has no quilt: a clear refusal, exit 2; an unknown display: the daemon's NOT_FOUND.
        err = self.run_example("turntable_capture.py", "--display", "builtin:integral-15-4k", expect=2).stderr
        self.assertIn("single view", err)
        err = self.run_example("turntable_capture.py", "--display", "nope", expect=1).stderr
        self.assertIn("nope", err)

    def test_stream_png_sequence(self):
        out_dir = os.path.join(self.work.name, "frames")
        out = self.run_example("stream_png_sequence.py", "--display", "tiny", "--scene", "demo.glb", "--fps", "10",
                               "--frames", "4", "--spin", "model", "--out", out_dir).stdout
        files = sorted(os.listdir(out_dir))
        self.assertEqual(files, [f"frame_{i:05d}.png" for i in range(4)])
        frames = [read_png(os.path.join(out_dir, f)) for f in files]
        for frame in frames:
            self.assertEqual(frame.shape, (48, 64, 3))  # RGB, one size: what a video encoder wants
        self.assertFalse(np.array_equal(frames[0], frames[3]), "the spinning node does not show")
        self.assertRegex(out, r"4 frames in [0-9.]+ s")
        self.assertIn("ffmpeg -framerate 10 -i", out)

    def test_move_node(self):
        prefix = os.path.join(self.work.name, "moved")
        out = self.run_example("move_node.py", "--scene", "demo.glb", "--display", "tiny", "--node", "model",
                               "--to", "0.25,0.1,0", "--out", prefix).stdout
        changed = float(re.search(r"([0-9.]+) % of the pixels changed", out).group(1))
        self.assertGreater(changed, 5.0)
        before, after = read_png(prefix + "_before.png"), read_png(prefix + "_after.png")
        self.assertEqual(before.shape, (48, 64, 4))
        self.assertFalse(np.array_equal(before, after))
        err = self.run_example("move_node.py", "--scene", "demo.glb", "--display", "tiny", "--node", "nope",
                               expect=2).stderr
        self.assertIn("refused the edit", err)
        self.assertIn("nope", err)


if __name__ == "__main__":
    unittest.main()
