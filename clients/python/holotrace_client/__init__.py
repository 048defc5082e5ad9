"""holotrace_client: a Python client of holotraced, the holotrace rendering daemon (clients/python/README.md).

    from holotrace_client import Client
    with Client("unix:/run/holotrace/holotraced.sock") as hc:
        scene = hc.load_scene("builtin:showcase")
        frame = hc.render(scene, "builtin:portrait", spp=1)   # numpy uint8 (views, height, width, 4)
"""

from .client import (CaptureProgress, Client, DaemonStatus, Display, DisplayInfo, PanelStatus, PresentProgress, Scene,
                     SceneUpdate, default_target, normalize_target)
from .errors import (Cancelled, DeadlineExceeded, HolotraceError, Internal, InvalidArgument, NotFound,
                     PermissionDenied, ProtocolError, ResourceExhausted, Unavailable, Unimplemented)
from .frames import Frame, FrameAssembler
from .matrices import identity, rotation_x, rotation_y, rotation_z, scaling, translation, world_values
from .png import decode_png, encode_png, read_png, srgb_encode, write_png
from .stream import FrameStream

__version__ = "0.1.0"

__all__ = [
    "CaptureProgress", "Cancelled", "Client", "DaemonStatus", "DeadlineExceeded", "Display", "DisplayInfo", "Frame",
    "FrameAssembler", "FrameStream", "HolotraceError", "Internal", "InvalidArgument", "NotFound", "PanelStatus",
    "PermissionDenied", "PresentProgress", "ProtocolError", "ResourceExhausted", "Scene", "SceneUpdate",
    "Unavailable", "Unimplemented", "decode_png", "default_target", "encode_png", "identity", "normalize_target",
    "read_png", "rotation_x", "rotation_y", "rotation_z", "scaling", "srgb_encode", "translation", "world_values",
    "write_png",
]
