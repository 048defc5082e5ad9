"""Client: one channel to holotraced and its RPCs as Python calls (docs/SERVICE.md for the protocol)."""

import os
from dataclasses import dataclass, field

import grpc

from ._proto import pb, pb_grpc
from .errors import HolotraceError, InvalidArgument, ProtocolError, error_from_rpc
from .frames import FrameAssembler, pixel_format
from .matrices import world_values
from .stream import FrameStream

UPLOAD_CHUNK_BYTES = 1 << 20        # below the daemon's default 4 MiB message limit
MAX_RECEIVE_BYTES = 64 << 20        # frames come in 1 MiB chunks; this only bounds a single odd message

CAPTURE_FORMATS = {"png": pb.CAPTURE_FORMAT_PNG, "exr": pb.CAPTURE_FORMAT_EXR}
CAPTURE_LAYOUTS = {"auto": pb.CAPTURE_LAYOUT_AUTO, "quilt": pb.CAPTURE_LAYOUT_QUILT, "views": pb.CAPTURE_LAYOUT_VIEWS}


def default_target():
    """$HOLOTRACE_TARGET, else the daemon's default socket: $XDG_RUNTIME_DIR/holotrace/holotraced.sock, else
    /run/holotrace/holotraced.sock (docs/SERVICE.md, `listen`)."""
    if os.environ.get("HOLOTRACE_TARGET"):
        return os.environ["HOLOTRACE_TARGET"]
    runtime = os.environ.get("XDG_RUNTIME_DIR")
    return "unix:" + os.path.join(runtime or "/run", "holotrace", "holotraced.sock")


def normalize_target(target):
    """A gRPC target: 'unix:/path' or 'unix:///path' as given, a bare absolute path becomes 'unix:/path', and
    'host:port' (the daemon listens on loopback only: 127.x.x.x or [::1]) stays as it is."""
    if not isinstance(target, str) or not target:
        raise ValueError(f"a daemon address is 'unix:/path/to/socket' or 'host:port', got {target!r}")
    if target.startswith("/"):
        return "unix:" + target
    return target


@dataclass
class Display:
    """A display the daemon serves (ListDisplays)."""
    id: str
    name: str
    model: str
    panel_width: int
    panel_height: int
    views: int
    # "builtin", "displays-dir", or a panel's calibration source: "config-file", "mounted-drive", "usb-hid"
    source: str = ""
    serial: str = ""  # a panel's serial (display id "device:SERIAL"), else ""


@dataclass
class DisplayInfo(Display):
    """GetDisplay: the summary plus optics. `optics` (lenticular only) has pitch, slope, center, view_cone_deg, dpi."""
    description: str = ""
    subpixel_bgr: bool = False
    optics: dict = None
    calibration_json: str = ""
    default_spp: int = 0


@dataclass
class Scene:
    """A scene session (LoadScene / UploadScene). `nodes` can be moved and `lights` (a count) changed by
    update_scene."""
    scene_id: str
    triangles: int
    nodes: list = field(default_factory=list)
    lights: int = 0
    reused: bool = False
    bvh_build_ms: float = 0.0
    load_ms: float = 0.0
    sah_cost: float = 0.0


@dataclass
class SceneUpdate:
    rebuild_ms: float
    sah_cost: float
    bvh_layout: str = ""  # "flattened" or "two-level" (docs/BVH.md §9.5)
    bvh_full_builds: int = 0
    bvh_instance_updates: int = 0  # node moves served without a BVH rebuild


@dataclass
class CaptureProgress:
    frames_done: int
    frames_total: int
    file: str  # relative to the daemon's output root


@dataclass
class PanelStatus:
    """A display sink of the daemon (a panel it shows frames on, docs/SERVICE.md §11)."""
    display_id: str
    attached: bool            # a window + swapchain is up on the panel's monitor
    monitor: str = ""         # RandR monitor name ("" while detached)
    geometry: str = ""        # "WxH+X+Y" on the X screen
    present_mode: str = ""    # "MAILBOX" or "FIFO"
    submitted: int = 0        # frames given to the sink
    presented: int = 0        # frames queued for display
    dropped: int = 0          # frames replaced by newer ones before they were shown
    last_error: str = ""      # why it is (or last was) detached
    x_display: str = ""


@dataclass
class PresentProgress:
    """One frame handed to a panel by present(): `panel` is the sink right after."""
    frame_id: int
    frames_done: int
    frames_total: int
    render_ms: float
    panel: PanelStatus


@dataclass
class DaemonStatus:
    version: str
    active_streams: int
    scenes_loaded: int
    devices: list
    pid: int = 0
    resident_kib: int = 0
    threads: int = 0
    panels: list = field(default_factory=list)  # PanelStatus of each display sink


def _id(thing, kind):
    """An id from a Scene / Display object or a string."""
    value = getattr(thing, "scene_id" if kind == "scene" else "id", thing)
    if not isinstance(value, str) or not value:
        raise ValueError(f"expected a {kind} (object or id string), got {thing!r}")
    return value


def _display(summary):
    return Display(summary.id, summary.name, summary.model, summary.panel_width, summary.panel_height,
                   max(1, summary.views), source=summary.source, serial=summary.serial)


def _scene(handle):
    return Scene(handle.scene_id, handle.triangles, list(handle.nodes), handle.lights, handle.reused,
                 handle.bvh_build_ms, handle.load_ms, handle.sah_cost)


def _panel(p):
    return PanelStatus(p.display_id, p.attached, p.monitor, p.geometry, p.present_mode, p.submitted, p.presented,
                       p.dropped, p.last_error, p.x_display)


# The first bytes of the files upload_scene recognises without a name: (magic, default name).
_CONTENT_NAMES = ((b"glTF", "upload.glb"), (b"\x89PNG\r\n\x1a\n", "upload.png"), (b"\x76\x2f\x31\x01", "upload.exr"))


def _upload_name(data):
    for magic, name in _CONTENT_NAMES:
        if data.startswith(magic):
            return name
    if data.lstrip()[:1] == b"{":
        return "upload.gltf"
    raise ValueError("upload_scene: name the file type with file_name='x.obj' (or .off/.glb/.gltf, or a quilt "
                     "'name_qs8x6a0.75.png')")


def _vec3(values, name):
    try:
        x, y, z = (float(v) for v in values)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be 3 numbers, got {values!r}") from None
    return pb.Vec3(x=x, y=y, z=z)


class Client:
    """A connection to holotraced.

        with Client("unix:/run/holotrace/holotraced.sock") as hc:
            scene = hc.load_scene("builtin:showcase")
            pixels = hc.render(scene, "builtin:portrait", spp=1)   # numpy (views, h, w, 4) uint8

    `timeout`: seconds for each unary call and each render (None = no limit); streams and captures run until they
    end. Failed calls raise HolotraceError subclasses (errors.py) chosen by the gRPC status code.
    """

    def __init__(self, target=None, timeout=120.0, options=None):
        self.target = normalize_target(target if target is not None else default_target())
        self.timeout = timeout
        channel_options = [("grpc.max_receive_message_length", MAX_RECEIVE_BYTES)] + list(options or [])
        self._channel = grpc.insecure_channel(self.target, options=channel_options)
        self._stub = pb_grpc.HolotraceStub(self._channel)
        self._closed = False

    # ---- connection ---------------------------------------------------------------------------------------------

    def close(self):
        """Closes the channel; later calls raise ValueError. Open streams are cancelled."""
        if not self._closed:
            self._closed = True
            self._channel.close()

    @property
    def closed(self):
        return self._closed

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def _check_open(self):
        if self._closed:
            raise ValueError("holotrace Client is closed")

    def _unary(self, rpc, request, timeout=None):
        self._check_open()
        try:
            return getattr(self._stub, rpc)(request, timeout=self.timeout if timeout is None else timeout)
        except grpc.RpcError as error:
            raise error_from_rpc(error, rpc) from None

    def wait_ready(self, timeout=10.0):
        """Waits until the daemon answers (its socket exists and Status succeeds); Unavailable after `timeout` s."""
        self._check_open()
        try:
            grpc.channel_ready_future(self._channel).result(timeout=timeout)
        except grpc.FutureTimeoutError:
            raise error_from_rpc(_Timeout(f"no daemon answered at {self.target} within {timeout} s"),
                                 "connect") from None
        return self.status()

    def status(self):
        r = self._unary("Status", pb.StatusRequest())
        devices = [{"name": d.name, "frames_rendered": d.frames_rendered, "last_frame_ms": d.last_frame_ms,
                    "mean_frame_ms": d.mean_frame_ms, "queued": d.queued} for d in r.devices]
        return DaemonStatus(r.version, r.active_streams, r.scenes_loaded, devices, r.pid, r.resident_kib, r.threads,
                            [_panel(p) for p in r.panels])

    # ---- displays and scenes ------------------------------------------------------------------------------------

    def displays(self):
        """The displays the daemon serves, as Display records."""
        return [_display(d) for d in self._unary("ListDisplays", pb.ListDisplaysRequest()).displays]

    def display(self, display):
        """GetDisplay: a DisplayInfo with optics, subpixel order and the calibration text."""
        r = self._unary("GetDisplay", pb.GetDisplayRequest(display_id=_id(display, "display")))
        base = _display(r.summary)
        optics = None
        if r.HasField("optics"):
            o = r.optics
            optics = {"pitch": o.pitch, "slope": o.slope, "center": o.center, "view_cone_deg": o.view_cone_deg,
                      "dpi": o.dpi}
        return DisplayInfo(**vars(base), description=r.description, subpixel_bgr=r.subpixel_bgr, optics=optics,
                           calibration_json=r.calibration_json, default_spp=r.default_spp)

    def load_scene(self, path):
        """A scene file below the daemon's scene root (a path relative to it), or 'builtin:NAME'."""
        return _scene(self._unary("LoadScene", pb.LoadSceneRequest(path=os.fspath(path))))

    def upload_scene(self, data, file_name=None):
        """Sends scene bytes (.glb, .gltf with embedded buffers, .obj, .off) or a quilt image (.png, .exr) to the
        daemon. `data`: bytes, or a path of a local file (then `file_name` defaults to its name). A quilt's layout comes
        from the name's `_qs{columns}x{rows}a{aspect}` tag (`file_name="take_qs8x6a0.75.png"`) or the metadata
        holotrace embeds in its quilts; its frames are the quilt interleaved for the display asked for. For bytes
        without `file_name` the type is taken from the content: GLB ('glTF' magic), glTF JSON ('{'), PNG or EXR
        (then only embedded metadata can give the layout); anything else needs `file_name`."""
        if isinstance(data, (str, os.PathLike)):
            file_name = file_name or os.path.basename(os.fspath(data))
            with open(data, "rb") as f:
                data = f.read()
        data = bytes(data)
        if file_name is None:
            file_name = _upload_name(data)

        def chunks():
            yield pb.UploadSceneChunk(info=pb.UploadInfo(file_name=file_name, total_bytes=len(data)))
            for offset in range(0, len(data), UPLOAD_CHUNK_BYTES):
                yield pb.UploadSceneChunk(data=data[offset:offset + UPLOAD_CHUNK_BYTES])

        return _scene(self._unary("UploadScene", chunks()))

    def unload_scene(self, scene):
        """Ends a scene session now (UnloadScene); the daemon also ends sessions left idle (docs/SERVICE.md §5).
        `scene`: a Scene or its scene_id."""
        self._unary("UnloadScene", pb.UnloadSceneRequest(scene_id=_id(scene, "scene")))

    def update_scene(self, scene, target=None, size=None, observer_distance=None, observer_height=None,
                     nodes=None, lights=None):
        """Edits one scene session (UpdateScene). target: focal-plane centre (x, y, z); size: focal-plane height;
        observer_distance / observer_height: the tracked viewer of a projector-array display; nodes: {name: world
        matrix} (4x4 numpy/rows, or 16 column-major values; matrices.py builds them); lights: {index: {"position":
        (x, y, z), "direction": ..., "color": ..., "intensity": v}}. All edits are checked by the daemon before any
        applies. Returns SceneUpdate(rebuild_ms, sah_cost, bvh_layout, bvh_full_builds, bvh_instance_updates)."""
        request = pb.UpdateSceneRequest(scene_id=_id(scene, "scene"))
        if target is not None:
            request.target.CopyFrom(_vec3(target, "target"))
        if size is not None:
            if not size > 0:
                raise ValueError(f"size must be > 0, got {size!r}")
            request.size = float(size)
        if observer_distance is not None:
            request.observer_distance = float(observer_distance)
        if observer_height is not None:
            request.observer_height = float(observer_height)
        for name, matrix in (nodes or {}).items():
            request.nodes.add(node=name, world=world_values(matrix))
        for index, edit in (lights or {}).items():
            light = request.lights.add(index=int(index))
            unknown = set(edit) - {"position", "direction", "color", "intensity"}
            if unknown:
                raise ValueError(f"lights[{index}]: unknown keys {sorted(unknown)} (position, direction, color, "
                                 "intensity)")
            for key in ("position", "direction", "color"):
                if key in edit:
                    getattr(light, key).CopyFrom(_vec3(edit[key], f"lights[{index}].{key}"))
            if "intensity" in edit:
                light.intensity = float(edit["intensity"])
        r = self._unary("UpdateScene", request)
        return SceneUpdate(r.rebuild_ms, r.sah_cost, r.bvh_layout, r.bvh_full_builds, r.bvh_instance_updates)

    # ---- frames -------------------------------------------------------------------------------------------------

    @staticmethod
    def _render_request(scene, display, spp, seed, quilt, format, refine_spp, refine_contrast,
                        reuse_after_edits=False):
        return pb.RenderRequest(scene_id=_id(scene, "scene"), display_id=_id(display, "display"),
                                format=pixel_format(format), spp=int(spp), seed=int(seed), quilt=bool(quilt),
                                refine_spp=int(refine_spp), refine_contrast=float(refine_contrast),
                                reuse_after_edits=bool(reuse_after_edits))

    def render_frame(self, scene, display, spp=0, seed=0, quilt=False, format="rgba8", refine_spp=0,
                     refine_contrast=0.0, timeout=None, reuse_after_edits=False):
        """One frame (RenderFrame) as a Frame: pixels (views, h, w, 4) for 'rgba8' / 'rgba16f', PNG bytes in
        .data for 'png'. spp 0 = the display's default; quilt = a lenticular display's quilt cameras.
        reuse_after_edits: keep what the next frame of the same request can reuse after update_scene() (a light
        edit re-shades cached hits, a node move re-traces only around the node; the frame is the same bits either
        way; Frame.reuse / .traced_targets say what it did), docs/SERVICE.md §4.2."""
        self._check_open()
        request = self._render_request(scene, display, spp, seed, quilt, format, refine_spp, refine_contrast,
                                       reuse_after_edits)
        assembler = FrameAssembler("RenderFrame")
        frame = None
        try:
            for part in self._stub.RenderFrame(request, timeout=self.timeout if timeout is None else timeout):
                frame = assembler.add(part) or frame
        except grpc.RpcError as error:
            raise error_from_rpc(error, "RenderFrame") from None
        if frame is None or assembler.pending:
            raise ProtocolError("the daemon ended the call without a complete frame", "RenderFrame")
        return frame

    def render(self, scene, display, spp=0, seed=0, quilt=False, format="rgba8", refine_spp=0,
               refine_contrast=0.0, timeout=None, reuse_after_edits=False):
        """One frame as a numpy array (views, height, width, 4), row 0 = top: uint8 sRGB ('rgba8') or float16
        linear ('rgba16f')."""
        if pixel_format(format) == pb.PIXEL_FORMAT_PNG:
            raise InvalidArgument("render() returns pixels: use format 'rgba8' or 'rgba16f', or render_png()",
                                  grpc.StatusCode.INVALID_ARGUMENT, "render")
        return self.render_frame(scene, display, spp, seed, quilt, format, refine_spp, refine_contrast,
                                 timeout, reuse_after_edits).pixels

    def render_png(self, scene, display, spp=0, seed=0, quilt=False, refine_spp=0, refine_contrast=0.0,
                   timeout=None):
        """One frame as the bytes of an 8-bit sRGB PNG (the quilt when a multi-view display's views form one)."""
        return self.render_frame(scene, display, spp, seed, quilt, "png", refine_spp, refine_contrast,
                                 timeout).data

    def stream(self, scene, display, fps=10.0, spp=0, seed=0, quilt=False, format="rgba8", refine_spp=0,
               refine_contrast=0.0, frames=None, mode="progressive", present_on="", reuse_after_edits=False):
        """StreamFrames as a FrameStream: iterate it for Frames, the newest one each time (stream.py); it ends after
        `frames` frames (None = until closed). Use it in a `with` block, or close() it. mode "progressive" (frames add
        samples until converged; a converged stream then sends nothing until the scene changes) or "independent"
        (a new frame every tick), docs/SERVICE.md §4.1. present_on: a display id with a panel sink (daemon config
        "present") that also shows every new frame on its panel (docs/SERVICE.md §11). reuse_after_edits: a
        progressive stream records from its first frame what a node move needs to restart only the targets near
        the node, even at the session's first move (docs/SERVICE.md §4.1)."""
        self._check_open()
        if not fps > 0:
            raise ValueError(f"fps must be > 0, got {fps!r}")
        modes = {"progressive": pb.STREAM_MODE_PROGRESSIVE, "independent": pb.STREAM_MODE_INDEPENDENT}
        if mode not in modes:
            raise ValueError(f"mode must be 'progressive' or 'independent', got {mode!r}")
        request = pb.StreamRequest(
            render=self._render_request(scene, display, spp, seed, quilt, format, refine_spp, refine_contrast,
                                        reuse_after_edits),
            frames_per_second=float(fps), mode=modes[mode], present_on=str(present_on))
        return FrameStream(self._stub.StreamFrames(request), frames)

    def capture(self, scene, display, name, frames=1, format="png", layout="auto", spp=0, seed=0, quilt=False,
                refine_spp=0, refine_contrast=0.0, progress=None):
        """Capture: the daemon writes `frames` frames as files under its output root (NAME_fNNNN.png, quilts as
        NAME_fNNNN_qs{c}x{r}a{aspect}.png + .json, views as NAME_fNNNN_v00.png ...). progress(CaptureProgress) is
        called as each file completes. Returns the CaptureProgress records (file paths relative to the output
        root). On an error, the files already reported are complete (the error says how many)."""
        self._check_open()
        try:
            capture_format, capture_layout = CAPTURE_FORMATS[format.lower()], CAPTURE_LAYOUTS[layout.lower()]
        except (KeyError, AttributeError):
            raise ValueError(f"capture format is one of {list(CAPTURE_FORMATS)} and layout one of "
                             f"{list(CAPTURE_LAYOUTS)}, got {format!r} / {layout!r}") from None
        request = pb.CaptureRequest(
            render=self._render_request(scene, display, spp, seed, quilt, "rgba8", refine_spp, refine_contrast),
            name=name, frames=int(frames), format=capture_format, layout=capture_layout)
        return self._progress_call("Capture", request, lambda p: CaptureProgress(p.frames_done, p.frames_total, p.file),
                                   progress)

    def present(self, scene, display, frames=1, rate=0.0, spp=0, seed=0, refine_spp=0, refine_contrast=0.0,
                progress=None):
        """Present: the daemon renders `frames` frames (seed, seed + 1, ...) of `display` and shows each on that
        display's panel, at `rate` frames per second (0 = as fast as they render); the last one stays up after the
        call. The display needs a panel sink (the daemon config's "present", docs/SERVICE.md §11); without one the
        daemon answers InvalidArgument. A quilt image session (load_scene / upload_scene of a quilt) plays the quilt.
        progress(PresentProgress) is called as each frame reaches the sink. Returns the PresentProgress records."""
        self._check_open()
        if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
            raise ValueError(f"frames must be an integer >= 1, got {frames!r}")
        if not rate >= 0:
            raise ValueError(f"rate must be >= 0 frames per second (0 = as fast as they render), got {rate!r}")
        request = pb.PresentRequest(
            render=self._render_request(scene, display, spp, seed, False, "rgba8", refine_spp, refine_contrast),
            frames=frames, frames_per_second=float(rate))
        return self._progress_call(
            "Present", request,
            lambda p: PresentProgress(p.frame_id, p.frames_done, p.frames_total, p.render_ms, _panel(p.panel)),
            progress)

    def _progress_call(self, rpc, request, record_of, progress):
        """A server-streaming call of progress messages: each becomes record_of(message), goes to progress(record)
        (if given) as it arrives, and all are returned; a failure raises its typed error."""
        done = []
        try:
            for message in getattr(self._stub, rpc)(request):
                record = record_of(message)
                done.append(record)
                if progress is not None:
                    progress(record)
        except grpc.RpcError as error:
            raise error_from_rpc(error, rpc) from None
        return done


class _Timeout(grpc.RpcError):
    """A client-side connect timeout, shaped like an RpcError so it maps to Unavailable."""

    def __init__(self, message):
        super().__init__(message)
        self._message = message

    def code(self):
        return grpc.StatusCode.UNAVAILABLE

    def details(self):
        return self._message


__all__ = ["Client", "Display", "DisplayInfo", "Scene", "SceneUpdate", "CaptureProgress", "DaemonStatus", "PanelStatus",
           "PresentProgress",
           "HolotraceError", "default_target", "normalize_target"]
