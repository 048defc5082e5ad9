"""holotrace_client without a daemon: PNG encoding and decoding, sRGB, matrices, frame assembly from protocol messages,
the error mapping, target names, and a closed or unreachable client."""

import json
import os
import struct
import unittest
import zlib

import grpc
import numpy as np

from daemon import EXAMPLES  # first: it puts the examples on sys.path
import demo_model  # noqa: E402
from demo_model import demo_glb  # noqa: E402
from holotrace_client import (Client, FrameAssembler, InvalidArgument, NotFound, PermissionDenied, ProtocolError,
                              Unavailable, decode_png, encode_png, normalize_target, rotation_y, srgb_encode,
                              translation, world_values)
from holotrace_client._proto import pb
from holotrace_client.errors import DeadlineExceeded, HolotraceError, error_from_rpc


def filtered_png(image, kinds):
    """A PNG whose row y uses filter kinds[y % len(kinds)], filtered here independently of the reader."""
    h, w, ch = image.shape
    rows, prior = [], np.zeros(w * ch, dtype=np.int32)
    for y in range(h):
        row = image[y].reshape(-1).astype(np.int32)
        left = np.concatenate([np.zeros(ch, dtype=np.int32), row[:-ch]])
        upper_left = np.concatenate([np.zeros(ch, dtype=np.int32), prior[:-ch]])
        kind = kinds[y % len(kinds)]
        if kind == 0:
            predicted = np.zeros_like(row)
        elif kind == 1:
            predicted = left
        elif kind == 2:
            predicted = prior
        elif kind == 3:
            predicted = (left + prior) // 2
        else:
            p = left + prior - upper_left
            pa, pb_, pc = np.abs(p - left), np.abs(p - prior), np.abs(p - upper_left)
            predicted = np.where((pa <= pb_) & (pa <= pc), left, np.where(pb_ <= pc, prior, upper_left))
        rows.append(bytes([kind]) + ((row - predicted) & 0xFF).astype(np.uint8).tobytes())
        prior = row
    colour = {1: 0, 2: 4, 3: 2, 4: 6}[ch]

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, colour, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b""))


class PngTest(unittest.TestCase):
    def test_round_trip_of_every_channel_count(self):
        rng = np.random.default_rng(7)
        for channels in (1, 2, 3, 4):
            image = rng.integers(0, 256, size=(5, 7, channels), dtype=np.uint8)
            np.testing.assert_array_equal(decode_png(encode_png(image)), image)

    def test_reader_undoes_all_five_row_filters(self):
        image = np.random.default_rng(3).integers(0, 256, size=(10, 9, 4), dtype=np.uint8)
        for kinds in ([0], [1], [2], [3], [4], [4, 3, 2, 1, 0]):
            np.testing.assert_array_equal(decode_png(filtered_png(image, kinds)), image, f"filters {kinds}")

    def test_float_images_are_srgb_encoded(self):
        # IEC 61966-2-1: 12.92 x below 0.0031308, 1.055 x^(1/2.4) - 0.055 above; 0.5 -> 0.7354 -> 188.
        np.testing.assert_array_equal(srgb_encode([0.0, 0.001, 0.5, 1.0, 2.0, -1.0]), [0, 3, 188, 255, 255, 0])
        image = np.full((2, 3, 4), 0.5, dtype=np.float32)
        decoded = decode_png(encode_png(image))
        np.testing.assert_array_equal(decoded[..., :3], 188)
        np.testing.assert_array_equal(decoded[..., 3], 128)  # alpha stays linear: 0.5 * 255 rounded

    def test_bad_inputs_are_errors(self):
        with self.assertRaises(ValueError):
            encode_png(np.zeros((2, 2, 5), dtype=np.uint8))
        with self.assertRaises(ValueError):
            encode_png(np.zeros((2, 2, 3), dtype=np.int32))
        with self.assertRaises(ValueError):
            decode_png(b"not a png")
        broken = bytearray(encode_png(np.zeros((2, 2, 3), dtype=np.uint8)))
        broken[20] ^= 0xFF  # inside IHDR: its CRC no longer matches
        with self.assertRaises(ValueError):
            decode_png(bytes(broken))


class MatrixTest(unittest.TestCase):
    def test_world_values_are_column_major(self):
        self.assertEqual(world_values(translation(1, 2, 3)),
                         [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1])
        flat = list(range(16))
        self.assertEqual(world_values(flat), [float(v) for v in flat])

    def test_rotation_y_turns_x_toward_minus_z(self):
        np.testing.assert_allclose(rotation_y(np.pi / 2) @ [1, 0, 0, 1], [0, 0, -1, 1], atol=1e-12)

    def test_bad_matrices_are_value_errors(self):
        with self.assertRaises(ValueError):
            world_values(np.eye(3))
        with self.assertRaises(ValueError):
            world_values([float("nan")] * 16)


def header_part(frame_id, width, height, views, fmt, total):
    return pb.FramePart(header=pb.FrameHeader(frame_id=frame_id, width=width, height=height, views=views,
                                              format=fmt, total_bytes=total, render_ms=2.5,
                                              stages=[pb.StageTime(name="trace", ms=1.0)]))


def chunk_part(frame_id, offset, data):
    return pb.FramePart(chunk=pb.FrameChunk(frame_id=frame_id, offset=offset, data=data))


class FrameAssemblerTest(unittest.TestCase):
    def test_chunks_make_views_of_pixels(self):
        pixels = np.arange(2 * 2 * 3 * 4, dtype=np.uint8).reshape(2, 2, 3, 4)
        data = pixels.tobytes()
        a = FrameAssembler()
        self.assertIsNone(a.add(header_part(7, 3, 2, 2, pb.PIXEL_FORMAT_RGBA8, len(data))))
        self.assertIsNone(a.add(chunk_part(7, 0, data[:20])))
        frame = a.add(chunk_part(7, 20, data[20:]))
        self.assertEqual((frame.frame_id, frame.views, frame.width, frame.height, frame.format), (7, 2, 3, 2, "rgba8"))
        np.testing.assert_array_equal(frame.pixels, pixels)
        self.assertEqual(frame.stages, {"trace": 1.0})
        self.assertFalse(a.pending)

    def test_half_floats_and_png(self):
        values = np.array([0.0, 0.5, 1.0, 2.0] * 2, dtype="<f2")
        a = FrameAssembler()
        a.add(header_part(1, 2, 1, 1, pb.PIXEL_FORMAT_RGBA16F, values.nbytes))
        frame = a.add(chunk_part(1, 0, values.tobytes()))
        self.assertEqual(frame.pixels.dtype, np.float16)
        np.testing.assert_array_equal(frame.pixels.reshape(-1), values)
        a.add(header_part(2, 4, 4, 1, pb.PIXEL_FORMAT_PNG, 3))
        frame = a.add(chunk_part(2, 0, b"abc"))
        self.assertIsNone(frame.pixels)
        self.assertEqual(frame.data, b"abc")

    def test_broken_streams_are_protocol_errors(self):
        a = FrameAssembler("RenderFrame")
        a.add(header_part(1, 1, 1, 1, pb.PIXEL_FORMAT_RGBA8, 4))
        with self.assertRaises(ProtocolError):
            a.add(chunk_part(1, 2, b"xy"))        # a gap
        a = FrameAssembler()
        a.add(header_part(1, 1, 1, 1, pb.PIXEL_FORMAT_RGBA8, 4))
        with self.assertRaises(ProtocolError):
            a.add(chunk_part(1, 0, b"12345"))     # past the end
        a = FrameAssembler()
        a.add(header_part(1, 1, 1, 1, pb.PIXEL_FORMAT_RGBA8, 4))
        with self.assertRaises(ProtocolError):
            a.add(header_part(2, 1, 1, 1, pb.PIXEL_FORMAT_RGBA8, 4))  # the first frame cut short
        a = FrameAssembler()
        with self.assertRaises(ProtocolError):
            a.add(chunk_part(3, 0, b"1234"))      # no header
        a = FrameAssembler()
        a.add(header_part(1, 2, 1, 1, pb.PIXEL_FORMAT_RGBA8, 4))
        with self.assertRaises(ProtocolError):
            a.add(chunk_part(1, 0, b"1234"))      # 2 pixels need 8 bytes


class FakeRpcError(grpc.RpcError):
    def __init__(self, code, details):
        self._code, self._details = code, details

    def code(self):
        return self._code

    def details(self):
        return self._details


class ErrorTest(unittest.TestCase):
    def test_status_codes_map_to_types(self):
        cases = {grpc.StatusCode.NOT_FOUND: (NotFound, LookupError),
                 grpc.StatusCode.PERMISSION_DENIED: (PermissionDenied, PermissionError),
                 grpc.StatusCode.INVALID_ARGUMENT: (InvalidArgument, ValueError),
                 grpc.StatusCode.UNAVAILABLE: (Unavailable, ConnectionError),
                 grpc.StatusCode.DEADLINE_EXCEEDED: (DeadlineExceeded, TimeoutError)}
        for code, types in cases.items():
            error = error_from_rpc(FakeRpcError(code, "display 'x' not found"), "GetDisplay")
            for t in types:
                self.assertIsInstance(error, t)
            self.assertEqual(error.code, code)
            self.assertEqual(error.details, "display 'x' not found")
            self.assertIn("GetDisplay: display 'x' not found", str(error))
        other = error_from_rpc(FakeRpcError(grpc.StatusCode.ABORTED, "x"))
        self.assertIs(type(other), HolotraceError)


class ClientOfflineTest(unittest.TestCase):
    def test_targets(self):
        self.assertEqual(normalize_target("/run/h.sock"), "unix:/run/h.sock")
        self.assertEqual(normalize_target("unix:/run/h.sock"), "unix:/run/h.sock")
        self.assertEqual(normalize_target("127.0.0.1:7000"), "127.0.0.1:7000")
        with self.assertRaises(ValueError):
            normalize_target("")

    def test_no_daemon_is_unavailable_and_a_closed_client_refuses(self):
        with Client("unix:/nonexistent/holotrace.sock", timeout=5) as client:
            with self.assertRaises(Unavailable):
                client.displays()
            with self.assertRaises(Unavailable):
                client.wait_ready(timeout=0.2)
        self.assertTrue(client.closed)
        with self.assertRaises(ValueError):
            client.displays()

    def test_client_side_argument_checks(self):
        with Client("unix:/nonexistent/holotrace.sock") as client:
            with self.assertRaises(ValueError):
                client.render("scene", "display", format="jpeg")
            with self.assertRaises(InvalidArgument):
                client.render("scene", "display", format="png")
            with self.assertRaises(ValueError):
                client.upload_scene(b"solid cube")          # type unknown without file_name
            with self.assertRaises(ValueError):
                client.update_scene("scene", nodes={"a": np.eye(3)})
            with self.assertRaises(ValueError):
                client.update_scene("scene", lights={0: {"colour": (1, 1, 1)}})
            with self.assertRaises(ValueError):
                client.stream("scene", "display", fps=0)
            with self.assertRaises(ValueError):
                client.capture("scene", "display", "n", layout="grid")
            with self.assertRaises(ValueError):
                client.render("", "display")


class DemoModelTest(unittest.TestCase):
    def test_demo_glb_is_a_well_formed_container(self):
        self.assertEqual(os.path.dirname(os.path.abspath(demo_model.__file__)), EXAMPLES)  # the shipped example
        data = demo_glb()
        magic, version, length = struct.unpack("<4sII", data[:12])
        self.assertEqual((magic, version, length), (b"glTF", 2, len(data)))
        json_length, kind = struct.unpack("<I4s", data[12:20])
        self.assertEqual(kind, b"JSON")
        gltf = json.loads(data[20:20 + json_length])
        bin_length, kind = struct.unpack("<I4s", data[20 + json_length:28 + json_length])
        self.assertEqual(kind, b"BIN\0")
        self.assertEqual(gltf["buffers"][0]["byteLength"], bin_length)
        self.assertEqual([n["name"] for n in gltf["nodes"]], ["model", "floor", "sun"])


if __name__ == "__main__":
    unittest.main()
