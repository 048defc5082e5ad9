"""FrameStream: the frames of a StreamFrames call as an iterator where the newest frame wins.

A background thread reads the call as fast as the daemon sends, so the daemon is never held back by a slow consumer
(its HTTP/2 window stays open, docs/SERVICE.md "Slow clients"), and keeps only the newest complete frame. next()
hands that frame out (waiting for one if none is new); frames replaced before you took them are counted in
Frame.skipped and FrameStream.skipped. close() (or leaving a `with` block, or reaching `frames`) cancels the call.
"""

import threading

import grpc

from .errors import error_from_rpc
from .frames import FrameAssembler

RPC = "StreamFrames"


class FrameStream:
    def __init__(self, call, frames=None):
        self._call = call
        self._limit = frames
        self._taken = 0
        self._latest = None
        self._skipped_since_taken = 0
        self._error = None
        self._done = False
        self._closing = False
        self._cond = threading.Condition()
        self.received = 0  # complete frames read from the daemon
        self.skipped = 0   # of those, replaced by a newer one before they were taken
        self._thread = threading.Thread(target=self._pump, name="holotrace-stream", daemon=True)
        self._thread.start()

    def _pump(self):
        assembler = FrameAssembler(RPC)
        try:
            for part in self._call:
                frame = assembler.add(part)
                if frame is None:
                    continue
                with self._cond:
                    self.received += 1
                    if self._latest is not None:
                        self.skipped += 1
                        self._skipped_since_taken += 1
                    self._latest = frame
                    self._cond.notify_all()
        except grpc.RpcError as error:
            with self._cond:
                if not (self._closing and error.code() == grpc.StatusCode.CANCELLED):
                    self._error = error_from_rpc(error, RPC)
        except Exception as error:  # a ProtocolError from the assembler
            with self._cond:
                self._error = error
            self._call.cancel()
        finally:
            with self._cond:
                self._done = True
                self._cond.notify_all()

    def __iter__(self):
        return self

    def __next__(self):
        frame = self.next()
        if frame is None:
            raise StopIteration
        return frame

    def next(self, timeout=None):
        """The newest complete frame not yet taken; waits for one up to `timeout` seconds (None = forever).
        Returns None when the stream has ended (closed, or `frames` taken) or the wait timed out; raises the typed
        error if the daemon ended the stream with one."""
        if self._limit is not None and self._taken >= self._limit:
            self.close()
            return None
        with self._cond:
            self._cond.wait_for(lambda: self._latest is not None or self._done, timeout)
            frame, self._latest = self._latest, None
            if frame is None:
                if self._error is not None:
                    raise self._error
                return None
            frame.skipped, self._skipped_since_taken = self._skipped_since_taken, 0
        self._taken += 1
        return frame

    def close(self):
        """Cancels the call (idempotent) and waits for the reader thread."""
        with self._cond:
            self._closing = True
        self._call.cancel()
        if threading.current_thread() is not self._thread:
            self._thread.join(timeout=10)

    @property
    def closed(self):
        return self._done

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass
