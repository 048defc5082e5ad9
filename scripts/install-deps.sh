#!/usr/bin/env bash
# Installs every Debian 12 package holotrace needs to build, test and benchmark.
# Nothing is downloaded outside Debian's archive. Safe to re-run.
set -euo pipefail
if [[ $(id -u) -ne 0 ]]; then
  echo "install-deps.sh: run as root (it calls apt-get)" >&2; exit 1
fi
export DEBIAN_FRONTEND=noninteractive
PKGS=(
  build-essential cmake ninja-build pkg-config git
  # the linker of both builds (CMakeLists.txt HOLOTRACE_USE_LLD): links about 3x faster than GNU ld
  lld
  # Vulkan loader, lavapipe (CPU Vulkan for CI), validation layers, SPIR-V compiler
  mesa-vulkan-drivers libvulkan-dev vulkan-tools vulkan-validationlayers glslang-tools spirv-tools
  # math, images, glTF, JSON
  libglm-dev libopenimageio-dev openimageio-tools libtinygltf-dev nlohmann-json3-dev
  # tests, benchmarks, comparator ray tracer
  libgtest-dev libgmock-dev libbenchmark-dev libembree-dev libtbb-dev
  # SHA-256 of rendered frames in tests and of the cluster start-up check (OpenSSL libcrypto)
  libssl-dev
  # cluster rendering across nodes: `mpirun -np N holotrace render|capture` and its tests (docs/CLUSTER.md)
  libopenmpi-dev openmpi-bin
  # test mesh: the Stanford bunny (69,666 triangles), /usr/share/glmark2/models/bunny.obj
  glmark2-data
  # benchmark meshes (CGAL armadillo, refined_elephant: scripts/fetch-meshes.sh) and plots (scripts/bench.sh)
  libcgal-demo gnuplot-nox
  # libFuzzer targets of the parsers (tests/fuzz, scripts/fuzz.sh): clang 14 and its runtime (libFuzzer, ASan)
  clang libclang-rt-14-dev
  # the format check of the C++ sources (tests/repo/check_format.py, ctest RepoFormat; .clang-format)
  clang-format
  # holotraced and its protocol (gRPC 1.51 + protobuf 3.21, docs/SERVICE.md §4); protobuf-compiler-grpc also brings
  # grpc_python_plugin, which generates the Python client's stubs at build time
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  # the Python client (clients/python) and its tests/examples: Debian's Python 3 with gRPC, protobuf and numpy
  # (frames arrive as numpy arrays); no PyPI. python3 also runs the repository checks (tests/repo)
  python3 python3-grpcio python3-protobuf python3-numpy
  # devices/ (docs/DISPLAY.md): libusb reads Gen1 panels' calibration over USB HID; umockdev emulates such a panel
  # for the end-to-end tests (tests/devices, DevicesUmockdevTests)
  libusb-1.0-0-dev umockdev
  # the display sink (present/, docs/DISPLAY.md): xcb + RandR headers; its tests run a private Xvfb and set RandR
  # monitors with xrandr (x11-xserver-utils)
  libxcb1-dev libxcb-randr0-dev xvfb x11-xserver-utils
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
echo "install-deps.sh: all ${#PKGS[@]} packages present"
