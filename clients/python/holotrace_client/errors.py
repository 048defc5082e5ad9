"""Typed errors of the holotrace client: every failed call raises a subclass of HolotraceError chosen by the gRPC
status code the daemon answered with (docs/SERVICE.md, "Errors"), so callers catch by type, never by parsing text.

The classes also derive from the closest Python built-in (NotFound is a LookupError, PermissionDenied a
PermissionError, DeadlineExceeded a TimeoutError, Unavailable a ConnectionError, InvalidArgument a ValueError), so
generic handlers work too.
"""

import grpc


class HolotraceError(Exception):
    """A call to holotraced failed. `code` is the grpc.StatusCode, `details` the daemon's message (it names the
    field, value or limit at fault and the fix)."""

    def __init__(self, details, code=grpc.StatusCode.UNKNOWN, rpc=""):
        self.details = details
        self.code = code
        self.rpc = rpc
        prefix = f"{rpc}: " if rpc else ""
        super().__init__(f"{prefix}{details} ({code.name})")


class InvalidArgument(HolotraceError, ValueError):
    """A malformed request field, a scene that does not parse, a display that cannot render (INVALID_ARGUMENT)."""


class NotFound(HolotraceError, LookupError):
    """Unknown display or scene id (NOT_FOUND)."""


class PermissionDenied(HolotraceError, PermissionError):
    """A path outside the daemon's scene root, a capture name with '/' (PERMISSION_DENIED)."""


class ResourceExhausted(HolotraceError):
    """A daemon limit (limits.*), a message over the size limit, or the output disk full (RESOURCE_EXHAUSTED)."""


class Unavailable(HolotraceError, ConnectionError):
    """No daemon at the address, or it is shutting down (UNAVAILABLE)."""


class Cancelled(HolotraceError):
    """The call was cancelled (CANCELLED)."""


class DeadlineExceeded(HolotraceError, TimeoutError):
    """The call took longer than its timeout (DEADLINE_EXCEEDED)."""


class Unimplemented(HolotraceError, NotImplementedError):
    """The daemon does not know this RPC: it is older than the client (UNIMPLEMENTED)."""


class Internal(HolotraceError):
    """A GPU or encoder failure inside the daemon (INTERNAL)."""


class ProtocolError(HolotraceError):
    """The daemon's answer breaks the protocol (a chunk outside its frame, a frame cut short); raised client-side."""

    def __init__(self, details, rpc=""):
        super().__init__(details, grpc.StatusCode.INTERNAL, rpc)


_BY_CODE = {
    grpc.StatusCode.INVALID_ARGUMENT: InvalidArgument,
    grpc.StatusCode.OUT_OF_RANGE: InvalidArgument,
    grpc.StatusCode.NOT_FOUND: NotFound,
    grpc.StatusCode.PERMISSION_DENIED: PermissionDenied,
    grpc.StatusCode.UNAUTHENTICATED: PermissionDenied,
    grpc.StatusCode.RESOURCE_EXHAUSTED: ResourceExhausted,
    grpc.StatusCode.UNAVAILABLE: Unavailable,
    grpc.StatusCode.CANCELLED: Cancelled,
    grpc.StatusCode.DEADLINE_EXCEEDED: DeadlineExceeded,
    grpc.StatusCode.UNIMPLEMENTED: Unimplemented,
    grpc.StatusCode.INTERNAL: Internal,
    grpc.StatusCode.DATA_LOSS: Internal,
}


def error_from_rpc(error, rpc=""):
    """The typed error for a grpc.RpcError (a status code we do not map gives HolotraceError itself)."""
    code = error.code() if hasattr(error, "code") else grpc.StatusCode.UNKNOWN
    details = error.details() if hasattr(error, "details") else str(error)
    return _BY_CODE.get(code, HolotraceError)(details or code.name.lower(), code, rpc)
