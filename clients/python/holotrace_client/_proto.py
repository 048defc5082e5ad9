"""The generated protocol modules (holotrace.v1.holotrace_pb2 and _pb2_grpc).

They are generated at build time from protocol/holotrace/v1/holotrace.proto by protoc and grpc_python_plugin (CMake
target holotrace_python_stubs) into <build>/clients/python/holotrace/v1/, which must be on sys.path next to this
package; <build>/clients/python/holotrace-python runs Python with both on the path.
"""

try:
    from holotrace.v1 import holotrace_pb2 as pb
    from holotrace.v1 import holotrace_pb2_grpc as pb_grpc
except ImportError as error:  # pragma: no cover - depends on the environment
    raise ImportError(
        "holotrace_client: the generated gRPC stubs (holotrace.v1.holotrace_pb2) are not importable: build them "
        "with `cmake --build build --target holotrace_python_stubs` and put build/clients/python on PYTHONPATH "
        "(or run build/clients/python/holotrace-python). Needs Debian's python3-grpcio and python3-protobuf. "
        f"Cause: {error}") from error

__all__ = ["pb", "pb_grpc"]
