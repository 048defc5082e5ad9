"""Frames as they arrive from RenderFrame / StreamFrames: a FrameHeader, then chunks of at most 1 MiB with offsets
(docs/SERVICE.md, "Protocol"). FrameAssembler puts the chunks together and checks them; Frame holds the bytes and,
for the raw formats, a numpy view of them shaped (views, height, width, 4), row 0 = top.
"""

from dataclasses import dataclass, field

import numpy as np

from ._proto import pb
from .errors import ProtocolError

# Pixel formats by their short names (RenderRequest.format).
PIXEL_FORMATS = {
    "rgba8": pb.PIXEL_FORMAT_RGBA8,      # sRGB-encoded 8-bit
    "rgba16f": pb.PIXEL_FORMAT_RGBA16F,  # linear half float
    "png": pb.PIXEL_FORMAT_PNG,          # one 8-bit sRGB PNG file
}
_NAMES = {value: name for name, value in PIXEL_FORMATS.items()}
_NAMES[pb.PIXEL_FORMAT_UNSPECIFIED] = "rgba8"
_REUSE = {pb.FRAME_REUSE_NONE: "none", pb.FRAME_REUSE_CACHED_PRIMARY_HITS: "cached-primary-hits",
          pb.FRAME_REUSE_PARTIAL_RETRACE: "partial-retrace"}
_STATES = {pb.STREAM_STATE_UNSPECIFIED: "independent", pb.STREAM_STATE_ACCUMULATING: "accumulating",
           pb.STREAM_STATE_CONVERGED: "converged"}
_DTYPES = {"rgba8": np.dtype(np.uint8), "rgba16f": np.dtype("<f2")}


def pixel_format(name):
    """The protocol enum of a format name ('rgba8', 'rgba16f', 'png'); ValueError names the choices."""
    try:
        return PIXEL_FORMATS[name.lower()]
    except (KeyError, AttributeError):
        raise ValueError(f"unknown pixel format {name!r} (expected one of {', '.join(PIXEL_FORMATS)})") from None


@dataclass
class Frame:
    """One rendered frame.

    pixels: numpy array (views, height, width, 4), row 0 = top: uint8 sRGB for 'rgba8', float16 linear for 'rgba16f';
    None for 'png', whose file bytes are in `data`. `dropped_frames` counts the frames the daemon skipped before this
    one (StreamFrames); `skipped` the complete frames this client replaced by newer ones before you took this one.
    """

    frame_id: int
    width: int
    height: int
    views: int
    format: str
    data: bytes
    pixels: object = None
    render_ms: float = 0.0
    queue_ms: float = 0.0
    dropped_frames: int = 0
    skipped: int = 0
    stages: dict = field(default_factory=dict)
    reuse: str = "none"       # RenderRequest.reuse_after_edits: "none", "cached-primary-hits" or "partial-retrace"
    traced_targets: int = 0   # targets the frame traced (a partial re-render: the dirty ones)
    # A progressive stream's frame (docs/SERVICE.md §4.1): "accumulating" or "converged" ("independent" otherwise),
    # the fewest and most samples of a target, and the targets a node move restarted (their sums start over).
    state: str = "independent"
    accumulated_spp: int = 0
    accumulated_spp_max: int = 0
    reset_targets: int = 0


class FrameAssembler:
    """Feed it FramePart messages in order; add() returns a Frame each time one is complete, else None."""

    def __init__(self, rpc=""):
        self._rpc = rpc
        self._header = None
        self._buffer = None
        self._received = 0

    @property
    def pending(self):
        """A frame has started and is not complete."""
        return self._header is not None

    def add(self, part):
        which = part.WhichOneof("part")
        if which == "header":
            if self._header is not None:
                raise ProtocolError(f"frame {self._header.frame_id} ended after {self._received} of "
                                    f"{self._header.total_bytes} bytes", self._rpc)
            self._start(part.header)
        elif which == "chunk":
            self._add_chunk(part.chunk)
        else:  # a part this client does not know (a newer daemon): skip it
            return None
        if self._header is not None and self._received == self._header.total_bytes:
            return self._finish()
        return None

    def _start(self, header):
        self._header = header
        self._buffer = bytearray(header.total_bytes)
        self._received = 0

    def _add_chunk(self, chunk):
        header = self._header
        if header is None or chunk.frame_id != header.frame_id:
            raise ProtocolError(f"chunk of frame {chunk.frame_id} outside its frame", self._rpc)
        end = chunk.offset + len(chunk.data)
        if chunk.offset != self._received or end > header.total_bytes:
            raise ProtocolError(f"chunk at offset {chunk.offset} (+{len(chunk.data)}) of frame {header.frame_id} "
                                f"after {self._received} of {header.total_bytes} bytes", self._rpc)
        self._buffer[chunk.offset:end] = chunk.data
        self._received = end

    def _finish(self):
        header, data = self._header, bytes(self._buffer)
        self._header, self._buffer, self._received = None, None, 0
        name = _NAMES.get(header.format, f"format-{header.format}")
        views = max(1, header.views)
        frame = Frame(frame_id=header.frame_id, width=header.width, height=header.height, views=views, format=name,
                      data=data, render_ms=header.render_ms, queue_ms=header.queue_ms,
                      dropped_frames=header.dropped_frames, stages={s.name: s.ms for s in header.stages},
                      reuse=_REUSE.get(header.reuse, f"reuse-{header.reuse}"), traced_targets=header.traced_targets,
                      state=_STATES.get(header.state, f"state-{header.state}"),
                      accumulated_spp=header.accumulated_spp, accumulated_spp_max=header.accumulated_spp_max,
                      reset_targets=header.reset_targets)
        dtype = _DTYPES.get(name)
        if dtype is not None:
            shape = (views, header.height, header.width, 4)
            expected = int(np.prod(shape)) * dtype.itemsize
            if len(data) != expected:
                raise ProtocolError(f"frame {header.frame_id}: {len(data)} bytes for {views} x {header.width}x"
                                    f"{header.height} {name} pixels ({expected} bytes)", self._rpc)
            frame.pixels = np.frombuffer(data, dtype=dtype).reshape(shape)
        return frame
