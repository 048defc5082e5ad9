"""holotrace_client against a real holotraced (daemon.py: temporary unix socket and a loopback TCP port, 64x48
lenticular panel, 3x2 capture grid, 3-projector wall, spp 1): every RPC, the pixel formats against each other and
against the daemon's own PNG encoder, latest-frame-wins streaming, capture progress, scene edits and typed errors."""

import os
import time
import unittest

import numpy as np

from daemon import Daemon, Xvfb
from demo_model import demo_glb
from holotrace_client import (Client, InvalidArgument, NotFound, PermissionDenied, decode_png, encode_png, read_png,
                              rotation_y, srgb_encode, translation)

QUILT_NAME = "take_qs4x3a1.333.png"  # the vendor's naming: 4 columns, 3 rows, rendered at the 64x48 panel's aspect


def quilt_png():
    """A 4x3 quilt of 16x12 views for the 64x48 panel, each view its own colour ramp (no holotrace metadata)."""
    y, x = np.mgrid[0:36, 0:64]
    view = (x // 16) + 4 * (2 - y // 12)  # view 0 bottom-left
    rgb = np.stack([(x * 4 + view * 20) % 256, (y * 7) % 256, (view * 21) % 256], axis=-1)
    return encode_png(rgb.astype(np.uint8))


class DaemonTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.daemon = Daemon(tcp=True).__enter__()
        cls.client = Client(cls.daemon.target)
        cls.scene = cls.client.upload_scene(demo_glb(), "demo.glb")

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.daemon.__exit__(None, None, None)

    def fresh_scene(self):
        """A session of its own (edits are per session), of the same bytes (the daemon shares the BVH)."""
        return self.client.load_scene("demo.glb")

    # ---- displays and scenes -----------------------------------------------------------------------------------

    def test_displays_and_display_details(self):
        by_id = {d.id: d for d in self.client.displays()}
        tiny = by_id["tiny"]
        self.assertEqual((tiny.model, tiny.panel_width, tiny.panel_height), ("lenticular", 64, 48))
        self.assertEqual((by_id["rig"].views, by_id["wall"].views), (6, 3))
        self.assertIn("builtin:portrait", by_id)
        self.assertEqual((tiny.source, tiny.serial, by_id["builtin:portrait"].source), ("displays-dir", "", "builtin"))
        info = self.client.display("tiny")
        self.assertAlmostEqual(info.optics["pitch"], 52.59)
        self.assertEqual(info.optics["dpi"], 324)
        self.assertIn("LKG-TEST-3", info.calibration_json)
        self.assertIsNone(self.client.display("rig").optics)
        with self.assertRaises(NotFound) as caught:
            self.client.display("nope")
        self.assertIn("nope", caught.exception.details)

    def test_load_and_upload(self):
        cube = self.client.load_scene("cube.obj")
        self.assertEqual(cube.triangles, 12)
        self.assertEqual(self.scene.triangles, 48)  # 4 boxes
        self.assertEqual(self.scene.nodes, ["model", "floor"])
        self.assertEqual(self.scene.lights, 1)
        again = self.client.load_scene("demo.glb")  # the same bytes as the upload
        self.assertTrue(again.reused)
        self.assertNotEqual(again.scene_id, self.scene.scene_id)
        with self.assertRaises(PermissionDenied):
            self.client.load_scene("../holotraced.json")
        with self.assertRaises(PermissionDenied):
            self.client.load_scene("/etc/passwd")
        with self.assertRaises(InvalidArgument):
            self.client.load_scene("missing.obj")
        with self.assertRaises(InvalidArgument):
            self.client.upload_scene(b"not a scene", "notes.txt")
        with self.assertRaises(InvalidArgument):
            self.client.upload_scene(b"glTF\x02\x00\x00\x00garbage")  # GLB magic, broken container

    def test_unload_scene_ends_the_session(self):
        cube = self.client.load_scene("cube.obj")
        self.client.unload_scene(cube)
        with self.assertRaises(NotFound):
            self.client.unload_scene(cube.scene_id)
        with self.assertRaises(NotFound):
            self.client.update_scene(cube, size=1.0)

    def test_loopback_tcp_target(self):
        with Client(self.daemon.tcp_target) as tcp:
            self.assertIn("tiny", [d.id for d in tcp.displays()])

    # ---- frames ------------------------------------------------------------------------------------------------

    def test_render_formats_agree(self):
        rgba8 = self.client.render(self.scene, "tiny", spp=1)
        self.assertEqual((rgba8.shape, rgba8.dtype), ((1, 48, 64, 4), np.uint8))
        self.assertTrue(np.all(rgba8[..., 3] == 255))
        self.assertGreater(rgba8[..., :3].std(), 5.0)  # a picture, not a flat fill
        half = self.client.render(self.scene, "tiny", spp=1, format="rgba16f")
        self.assertEqual((half.shape, half.dtype), ((1, 48, 64, 4), np.float16))
        self.assertTrue(np.all(np.isfinite(half)))
        # The same frame (same seed) once sRGB-encoded by the daemon, once linear: within one code after encoding.
        diff = np.abs(srgb_encode(half[..., :3].astype(np.float32)).astype(int) - rgba8[..., :3])
        self.assertLessEqual(diff.max(), 1)

    def test_multi_view_frames_and_the_daemons_png(self):
        views = self.client.render(self.scene, "rig", spp=1)
        self.assertEqual(views.shape, (6, 16, 24, 4))
        self.assertFalse(np.array_equal(views[0], views[5]))  # cameras 0.1 apart see the model differently
        self.assertEqual(self.client.render(self.scene, "wall", spp=1).shape, (3, 12, 20, 4))
        # The daemon's PNG (its own encoder) of the same frame is the 3x2 quilt of those views, view 0 bottom-left.
        quilt = decode_png(self.client.render_png(self.scene, "rig", spp=1))
        self.assertEqual(quilt.shape[:2], (32, 72))
        for view in range(6):
            column, row_from_bottom = view % 3, view // 3
            top = (1 - row_from_bottom) * 16
            tile = quilt[top:top + 16, column * 24:(column + 1) * 24, :3]
            self.assertLessEqual(np.abs(tile.astype(int) - views[view, :, :, :3]).max(), 1, f"view {view}")

    def test_request_errors(self):
        with self.assertRaises(InvalidArgument) as caught:
            self.client.render(self.scene, "tiny", spp=100000)
        self.assertIn("render.spp", caught.exception.details)
        with self.assertRaises(NotFound):
            self.client.render("s999-0000000000000000", "tiny")
        with self.assertRaises(NotFound):
            self.client.render(self.scene, "nope")
        with self.assertRaises(InvalidArgument):
            self.client.render(self.scene, "wall", quilt=True)  # quilt cameras exist for lenticular displays only

    def test_stream_hands_out_the_newest_frame(self):
        with self.client.stream(self.scene, "tiny", fps=20, spp=1, frames=4, mode="independent") as stream:
            ids = []
            for frame in stream:
                ids.append(frame.frame_id)
                self.assertEqual(frame.pixels.shape, (1, 48, 64, 4))
                if len(ids) > 1:
                    # 0.6 s at 20 fps is ~12 frames: the ones this reader slept through were replaced, not queued.
                    self.assertGreaterEqual(frame.skipped + frame.dropped_frames, 1)
                time.sleep(0.6)
            self.assertEqual(len(ids), 4)
            self.assertEqual(ids, sorted(ids))
            self.assertGreater(stream.received, 4)
        self.assertTrue(stream.closed)
        deadline = time.monotonic() + 10
        while self.client.status().active_streams and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertEqual(self.client.status().active_streams, 0)  # the cancel reached the daemon

    def test_stream_errors_arrive_as_types(self):
        with self.client.stream(self.scene, "nope", fps=5) as stream:
            with self.assertRaises(NotFound):
                next(stream)

    def test_capture_reports_progress_and_writes_complete_files(self):
        seen = []
        done = self.client.capture(self.scene, "rig", "take", frames=2, progress=seen.append)
        self.assertEqual(seen, done)
        pngs = [p.file for p in done if p.file.endswith(".png")]
        self.assertEqual(pngs, ["take_f0000_qs3x2a1.5.png", "take_f0001_qs3x2a1.5.png"])
        self.assertEqual([p.frames_done for p in done if p.file.endswith(".png")], [1, 2])
        for name in pngs:
            self.assertEqual(read_png(os.path.join(self.daemon.output_root, name)).shape[:2], (32, 72))
        with self.assertRaises(PermissionDenied):
            self.client.capture(self.scene, "rig", "../escape")

    # ---- scene edits -------------------------------------------------------------------------------------------

    def test_update_scene_moves_nodes_and_lights_for_this_session_only(self):
        scene = self.fresh_scene()
        before = self.client.render(scene, "tiny", spp=1)
        update = self.client.update_scene(scene, nodes={"model": translation(0.3, 0.0, 0.0) @ rotation_y(0.7)})
        self.assertGreater(update.rebuild_ms, 0.0)
        moved = self.client.render(scene, "tiny", spp=1)
        self.assertGreater(np.mean(np.any(moved != before, axis=-1)), 0.05)
        # Another session of the same content keeps the model where it was.
        np.testing.assert_array_equal(self.client.render(self.fresh_scene(), "tiny", spp=1), before)
        self.client.update_scene(scene, lights={0: {"intensity": 0.0}})
        dark = self.client.render(scene, "tiny", spp=1)
        self.assertLess(dark[..., :3].mean(), moved[..., :3].mean())
        with self.assertRaises(InvalidArgument) as caught:
            self.client.update_scene(scene, nodes={"no-such-node": translation(0, 0, 0)})
        self.assertIn("no-such-node", caught.exception.details)
        with self.assertRaises(InvalidArgument):
            self.client.update_scene(scene, lights={5: {"intensity": 1.0}})

    def test_frames_reuse_their_predecessor_after_edits(self):
        scene = self.fresh_scene()
        self.client.update_scene(scene, lights={0: {"intensity": 1.0}})  # the session's own renderer from here on
        first = self.client.render_frame(scene, "tiny", spp=1, reuse_after_edits=True)
        self.assertEqual(first.reuse, "none")
        self.client.update_scene(scene, nodes={"model": translation(0.1, 0.0, 0.0)})
        moved = self.client.render_frame(scene, "tiny", spp=1, reuse_after_edits=True)
        full = self.client.render_frame(scene, "tiny", spp=1)
        self.assertEqual((moved.reuse, full.reuse), ("partial-retrace", "none"))
        self.assertLess(moved.traced_targets, full.traced_targets)
        np.testing.assert_array_equal(moved.pixels, full.pixels)

    def test_a_reusing_progressive_stream_restarts_only_near_the_first_move(self):
        scene = self.fresh_scene()

        def until_converged(frames):
            for frame in frames:
                if frame.state == "converged":
                    return frame
            self.fail("the stream ended before it converged")

        with self.client.stream(scene, "tiny", fps=100, spp=2, format="rgba16f", reuse_after_edits=True) as frames:
            self.assertEqual(until_converged(frames).reset_targets, 0)
            self.client.update_scene(scene, nodes={"model": translation(0.05, 0.0, 0.0)})
            first = next(iter(frames))
            while first.state == "converged":  # the converged frame may still be on its way
                first = next(iter(frames))
            targets = first.width * first.height * 3
            self.assertGreater(first.reset_targets, 0)
            self.assertLess(first.reset_targets, targets)  # some targets kept their samples
            self.assertGreater(first.accumulated_spp_max, first.accumulated_spp)

    # ---- quilt images and panels (docs/SERVICE.md §11-12) -----------------------------------------------------

    def test_upload_quilt_renders_as_the_loaded_file(self):
        with open(os.path.join(self.daemon.scene_root, QUILT_NAME), "wb") as f:
            f.write(quilt_png())
        loaded = self.client.load_scene(QUILT_NAME)
        uploaded = self.client.upload_scene(quilt_png(), QUILT_NAME)
        self.assertEqual((uploaded.triangles, uploaded.reused), (0, True))  # the loaded content, shared
        panel = self.client.render(uploaded, "tiny")
        np.testing.assert_array_equal(panel, self.client.render(loaded, "tiny"))
        self.assertGreater(len(np.unique(panel[0, :, :, 0])), 16)  # the views interleaved, not one flat view
        with self.assertRaises(InvalidArgument) as caught:
            self.client.upload_scene(quilt_png())  # a PNG without a _qs name or holotrace metadata: no layout
        self.assertIn("info.file_name", caught.exception.details)
        self.assertIn("_qs{columns}x{rows}a{aspect}", caught.exception.details)
        wide = self.client.upload_scene(quilt_png(), "wide_qs4x3a1.777.png")  # made for a 16:9 panel
        with self.assertRaises(InvalidArgument) as caught:
            self.client.render(wide, "tiny")
        self.assertIn("quilt aspect", caught.exception.details)

    def test_present_needs_a_panel_sink(self):
        with self.assertRaises(InvalidArgument) as caught:  # this daemon's config lists no "present" panels
            self.client.present(self.scene, "tiny")
        self.assertIn("has no panel sink", caught.exception.details)
        self.assertEqual(self.client.status().panels, [])
        for bad in ({"frames": 0}, {"frames": 1.5}, {"rate": -1.0}):
            with self.assertRaises(ValueError):
                self.client.present(self.scene, "tiny", **bad)

    def test_closed_client(self):
        with Client(self.daemon.target) as client:
            self.assertTrue(client.displays())
        self.assertTrue(client.closed)
        with self.assertRaises(ValueError):
            client.load_scene("cube.obj")


class PresentOnXvfbTest(unittest.TestCase):
    """present() against a daemon whose "tiny" display has a panel sink on a private Xvfb (a 64x48 screen: its one
    RandR monitor is the panel, picked by size). The pixels on the monitor are compared with `holotrace interleave`'s
    panel by the C++ test PresentQuiltTests; here the client's side: progress records, the sink's status."""

    @classmethod
    def setUpClass(cls):
        cls.xvfb = Xvfb(64, 48).__enter__()
        try:
            cls.daemon = Daemon(config={"present": ["tiny"], "x_display": cls.xvfb.display}).__enter__()
        except BaseException:
            cls.xvfb.__exit__(None, None, None)
            raise
        cls.client = Client(cls.daemon.target)

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.daemon.__exit__(None, None, None)
        cls.xvfb.__exit__(None, None, None)

    def test_present_an_uploaded_quilt_with_progress(self):
        quilt = self.client.upload_scene(quilt_png(), QUILT_NAME)
        seen = []
        done = self.client.present(quilt, "tiny", frames=3, rate=30.0, progress=seen.append)
        self.assertEqual(seen, done)
        self.assertEqual([(p.frames_done, p.frames_total) for p in done], [(1, 3), (2, 3), (3, 3)])
        self.assertEqual([p.panel.display_id for p in done], ["tiny"] * 3)
        self.assertEqual(done[-1].panel.submitted, 3)
        self.assertEqual([p.frame_id for p in done], sorted(set(p.frame_id for p in done)))
        deadline = time.monotonic() + 20
        panel = self.client.status().panels[0]
        while not (panel.attached and panel.presented >= 1) and time.monotonic() < deadline:
            time.sleep(0.05)
            panel = self.client.status().panels[0]
        self.assertTrue(panel.attached, panel.last_error)
        self.assertGreaterEqual(panel.presented, 1)
        self.assertEqual((panel.geometry, panel.x_display), ("64x48+0+0", self.xvfb.display))
        with self.assertRaises(InvalidArgument):  # the wall has no sink (and no single panel image)
            self.client.present(quilt, "wall")

    def test_stream_present_on_shows_the_frames_on_the_panel(self):
        scene = self.client.load_scene("builtin:sphere")
        before = self.client.status().panels[0].submitted
        with self.client.stream(scene, "tiny", fps=20.0, spp=1, frames=2, mode="independent",
                                present_on="tiny") as frames:
            self.assertEqual(len(list(frames)), 2)
        self.assertGreaterEqual(self.client.status().panels[0].submitted, before + 2)
        with self.assertRaises(InvalidArgument):
            with self.client.stream(scene, "tiny", frames=1, present_on="no-such-display") as frames:
                list(frames)


if __name__ == "__main__":
    unittest.main()
