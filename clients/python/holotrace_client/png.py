"""A small PNG writer and reader with nothing but the standard library (zlib, struct), for frames as numpy arrays.

write_png: 8-bit RGB or RGBA (or grey), non-interlaced, written atomically (a temporary file in the target directory,
renamed into place, so an interrupted run never leaves a partial image). Float arrays are taken as linear light and
encoded with the sRGB transfer function (IEC 61966-2-1), as holotrace's own PNG output is.
read_png: 8-bit grey / grey+alpha / RGB / RGBA, non-interlaced, all five row filters (what libpng writes); enough
for frames and captures of holotrace, not a general decoder (16-bit, palette and interlaced files raise ValueError).
"""

import os
import struct
import tempfile
import zlib

import numpy as np

_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_COLOUR_TYPES = {1: 0, 2: 4, 3: 2, 4: 6}   # channels -> PNG colour type
_CHANNELS = {v: k for k, v in _COLOUR_TYPES.items()}


def srgb_encode(linear):
    """Linear [0, 1] values -> 8-bit sRGB codes (clamped, rounded)."""
    x = np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0)
    v = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)
    return np.rint(v * 255.0).astype(np.uint8)


def _chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def encode_png(image):
    """PNG file bytes of an (h, w), (h, w, 1|2|3|4) uint8 image, or of a float image in linear light (sRGB-encoded;
    alpha, the 4th channel, is stored linearly)."""
    a = np.asarray(image)
    if a.ndim == 2:
        a = a[:, :, None]
    if a.ndim != 3 or a.shape[2] not in _COLOUR_TYPES or a.shape[0] == 0 or a.shape[1] == 0:
        raise ValueError(f"encode_png: expected an (h, w[, 1-4]) image, got shape {a.shape}")
    if a.dtype != np.uint8:
        if not np.issubdtype(a.dtype, np.floating):
            raise ValueError(f"encode_png: pixels must be uint8 or floating point, got {a.dtype}")
        colour = srgb_encode(a[:, :, :3] if a.shape[2] >= 3 else a[:, :, :1])
        extra = np.rint(np.clip(a[:, :, colour.shape[2]:], 0.0, 1.0) * 255.0).astype(np.uint8)
        a = np.concatenate([colour, extra], axis=2)
    h, w, channels = a.shape
    raw = np.zeros((h, 1 + w * channels), dtype=np.uint8)  # filter byte 0 (None) per row
    raw[:, 1:] = a.reshape(h, w * channels)
    header = struct.pack(">IIBBBBB", w, h, 8, _COLOUR_TYPES[channels], 0, 0, 0)
    return (_SIGNATURE + _chunk(b"IHDR", header) + _chunk(b"IDAT", zlib.compress(raw.tobytes(), 6)) +
            _chunk(b"IEND", b""))


def write_file_atomically(path, data):
    """Writes bytes to `path` through a temporary file in the same directory and a rename."""
    directory = os.path.dirname(os.path.abspath(path))
    fd, temp = tempfile.mkstemp(prefix=".tmp-", suffix=".part", dir=directory)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(temp, path)
    except BaseException:
        if os.path.exists(temp):
            os.unlink(temp)
        raise


def write_png(path, image):
    """Writes an image (see encode_png) to `path` atomically."""
    write_file_atomically(path, encode_png(image))


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def _unfilter(kind, row, prior, bpp):
    if kind == 0:
        return row
    if kind == 1:  # Sub: a running sum per channel along the row
        r = np.frombuffer(row, dtype=np.uint8).reshape(-1, bpp).astype(np.uint32)
        return (np.cumsum(r, axis=0) & 0xFF).astype(np.uint8).tobytes()
    if kind == 2:  # Up
        return (np.frombuffer(row, dtype=np.uint8) + np.frombuffer(prior, dtype=np.uint8)).tobytes()
    out = bytearray(row)
    for i in range(len(out)):
        left = out[i - bpp] if i >= bpp else 0
        up = prior[i]
        if kind == 1:
            out[i] = (out[i] + left) & 0xFF
        elif kind == 2:
            out[i] = (out[i] + up) & 0xFF
        elif kind == 3:
            out[i] = (out[i] + ((left + up) >> 1)) & 0xFF
        elif kind == 4:
            out[i] = (out[i] + _paeth(left, up, prior[i - bpp] if i >= bpp else 0)) & 0xFF
        else:
            raise ValueError(f"read_png: unknown row filter {kind}")
    return bytes(out)


def decode_png(data):
    """(h, w, channels) uint8 array of PNG file bytes (8-bit, non-interlaced grey/grey+alpha/RGB/RGBA)."""
    if data[:8] != _SIGNATURE:
        raise ValueError("read_png: not a PNG file (bad signature)")
    pos, header, idat = 8, None, bytearray()
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if len(body) != length or zlib.crc32(kind + body) & 0xFFFFFFFF != struct.unpack(
                ">I", data[pos + 8 + length:pos + 12 + length])[0]:
            raise ValueError(f"read_png: chunk {kind!r} is cut short or its CRC is wrong")
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + length
    if header is None:
        raise ValueError("read_png: no IHDR chunk")
    w, h, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in _CHANNELS or interlace != 0:
        raise ValueError(f"read_png: only 8-bit non-interlaced grey/RGB(A) is supported (depth {depth}, "
                         f"colour type {colour}, interlace {interlace})")
    channels = _CHANNELS[colour]
    raw = zlib.decompress(bytes(idat))
    stride = w * channels
    if len(raw) != h * (stride + 1):
        raise ValueError(f"read_png: {len(raw)} bytes of pixel data for {w}x{h}x{channels}")
    rows, prior = [], bytes(stride)
    for y in range(h):
        start = y * (stride + 1)
        prior = _unfilter(raw[start], raw[start + 1:start + 1 + stride], prior, channels)
        rows.append(prior)
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(h, w, channels)


def read_png(path):
    with open(path, "rb") as f:
        return decode_png(f.read())
