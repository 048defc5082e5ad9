"""A real holotraced for the Python tests: a temporary directory with small displays, a scene root and an output root,
the daemon listening on a unix socket inside it, started as a child process and ended by its PID (SIGTERM, then
SIGKILL if it does not exit within 30 s). The binary comes from $HOLOTRACED (set by tests/python/CMakeLists.txt).
"""

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.normpath(os.path.join(HERE, "..", "..", "clients", "python", "examples"))
sys.path.insert(0, EXAMPLES)

from holotrace_client import Client, HolotraceError  # noqa: E402
from demo_model import demo_glb  # noqa: E402

# A 64x48 lenticular panel with the Portrait's calibration style, a 3x2 capture grid of 24x16 cameras (its views form
# a quilt) and a 3-projector HPO wall of 20x12 images.
DISPLAYS = {
    "tiny": {"name": "tiny", "model": "lenticular", "spp": 1, "calibration": {
        "configVersion": "3.0", "serial": "LKG-TEST-3", "pitch": 52.59, "slope": -7.21, "center": 0.4,
        "viewCone": 40, "invView": 1, "verticalAngle": 0, "DPI": 324, "screenW": 64, "screenH": 48, "flipImageX": 0,
        "flipImageY": 0, "flipSubp": 0, "CellPatternMode": 0, "subpixelCells": []}},
    "rig": {"name": "rig", "model": "capture-grid", "spp": 1, "captureGrid": {
        "columns": 3, "rows": 2, "spacing": [0.1, 0.1], "distance": 3, "window": {"width": 2.4, "height": 1.6},
        "image": {"width": 24, "height": 16}}},
    "wall": {"name": "wall", "model": "projector-array", "spp": 1, "projectorArray": {
        "screen": {"width": 160, "height": 90}, "observerDistance": 300, "observerHeight": 0,
        "angularScattering": "auto", "image": {"width": 20, "height": 12},
        "projectors": [{"position": [-10, 0, -180]}, {"position": [0, 0, -180]}, {"position": [10, 0, -180]}]}},
}

CUBE_OBJ = """v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 0.5 -0.5
v -0.5 -0.5 0.5
v 0.5 -0.5 0.5
v 0.5 0.5 0.5
v -0.5 0.5 0.5
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 4 7 3
f 4 8 7
f 1 5 8
f 1 8 4
f 2 3 7
f 2 7 6
"""


def free_loopback_port():
    """A TCP port on 127.0.0.1 that was free a moment ago (the daemon binds it right after)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Daemon:
    """`with Daemon() as d:` ... d.target, d.output_root, d.scene_root. Raises on leaving if the daemon did not exit 0
    on SIGTERM (the daemon's own clean-shutdown contract, docs/SERVICE.md "Signals")."""

    def __init__(self, exe=None, limits=None, tcp=False, config=None):
        self.exe = exe or os.environ.get("HOLOTRACED")
        if not self.exe or not os.access(self.exe, os.X_OK):
            raise RuntimeError(f"no holotraced binary: set HOLOTRACED (got {self.exe!r})")
        self.limits = limits or {}
        self.extra_config = config or {}  # more daemon config fields, e.g. {"present": ["tiny"], "x_display": ":5"}
        self.tcp_target = f"127.0.0.1:{free_loopback_port()}" if tcp else None
        self.process = None
        self.exit_code = None

    def __enter__(self):
        self.dir = tempfile.mkdtemp(prefix="ht-py-")
        os.chmod(self.dir, 0o700)
        self.scene_root = os.path.join(self.dir, "scenes")
        self.output_root = os.path.join(self.dir, "out")
        for sub in ("displays", "scenes", "out", "run"):
            os.makedirs(os.path.join(self.dir, sub))
        for name, config in DISPLAYS.items():
            with open(os.path.join(self.dir, "displays", name + ".json"), "w") as f:
                json.dump(config, f)
        with open(os.path.join(self.scene_root, "cube.obj"), "w") as f:
            f.write(CUBE_OBJ)
        with open(os.path.join(self.scene_root, "demo.glb"), "wb") as f:
            f.write(demo_glb())
        self.socket = os.path.join(self.dir, "run", "d.sock")
        self.target = "unix:" + self.socket
        listen = [self.target] + ([self.tcp_target] if self.tcp_target else [])
        config = {"displays_dir": "displays", "scene_root": "scenes", "output_root": "out", "listen": listen,
                  "limits": self.limits, **self.extra_config}
        config_path = os.path.join(self.dir, "holotraced.json")
        with open(config_path, "w") as f:
            json.dump(config, f)
        self.log_path = os.path.join(self.dir, "holotraced.log")
        self._log = open(self.log_path, "wb")
        self.process = subprocess.Popen([self.exe, "--config", config_path], stdout=self._log,
                                        stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
        try:
            self._wait_ready()
        except BaseException:
            self.stop()
            self._cleanup()
            raise
        return self

    def _wait_ready(self, seconds=60.0):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"holotraced exited with {self.process.returncode} at start:\n{self.log()}")
            if os.path.exists(self.socket):
                try:
                    with Client(self.target, timeout=2.0) as client:
                        client.status()
                    return
                except HolotraceError:
                    pass
            time.sleep(0.05)
        raise RuntimeError(f"holotraced did not answer within {seconds} s:\n{self.log()}")

    def log(self):
        self._log.flush()
        with open(self.log_path, "rb") as f:
            return f.read().decode(errors="replace")[-4000:]

    def stop(self):
        """SIGTERM to the daemon's PID, SIGKILL after 30 s; returns its exit code (128 + signal if killed)."""
        if self.process is None or self.exit_code is not None:
            return self.exit_code
        self.process.send_signal(signal.SIGTERM)
        try:
            self.exit_code = self.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
            self.exit_code = 128 + signal.SIGKILL
        return self.exit_code

    def _cleanup(self):
        self._log.close()
        shutil.rmtree(self.dir, ignore_errors=True)

    def __exit__(self, exc_type, exc, tb):
        code = self.stop()
        log = self.log()
        self._cleanup()
        if exc_type is None and code != 0:
            raise AssertionError(f"holotraced exited with {code} on SIGTERM (expected 0):\n{log}")
        return False


class Xvfb:
    """`with Xvfb(64, 48) as x:` ... x.display (":N"): a private X server with one screen of that size, whose RandR
    monitor "screen" is the panel a daemon's display sink picks by size. Started on a free display number
    (-displayfd), with -noreset, ended by its PID (SIGTERM, SIGKILL after 10 s)."""

    def __init__(self, width, height):
        self.size = f"{width}x{height}x24"
        self.process = None

    def __enter__(self):
        read_end, write_end = os.pipe()
        try:
            self.process = subprocess.Popen(
                ["Xvfb", "-displayfd", str(write_end), "-screen", "0", self.size, "-noreset", "-nolisten", "tcp"],
                pass_fds=(write_end,), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL)
        except FileNotFoundError:
            os.close(read_end)
            os.close(write_end)
            raise RuntimeError("no Xvfb: install the xvfb package (scripts/install-deps.sh)") from None
        os.close(write_end)
        number = b""
        with os.fdopen(read_end, "rb") as announced:  # Xvfb writes the display number once it accepts clients
            number = announced.readline().strip()
        if not number.isdigit():
            self.__exit__(None, None, None)
            raise RuntimeError("Xvfb did not start (no display number announced)")
        self.display = ":" + number.decode()
        return self

    def __exit__(self, exc_type, exc, tb):
        if self.process is not None and self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        return False
