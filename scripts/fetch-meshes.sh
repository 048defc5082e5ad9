#!/usr/bin/env bash
# Extracts the benchmark meshes from Debian's CGAL data tarball into assets/ (gitignored). Nothing is downloaded:
# the tarball ships with libcgal-demo (scripts/install-deps.sh) as /usr/share/doc/libcgal-{dev,demo}/data.tar.gz.
#   assets/armadillo.off         (CGAL data/meshes/armadillo.off)
#   assets/refined_elephant.off  (CGAL data/meshes/refined_elephant.off)
# Usage: scripts/fetch-meshes.sh [--help]. Safe to re-run (skips meshes already present).
set -euo pipefail
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0
fi
if [[ $# -gt 0 ]]; then echo "fetch-meshes.sh: unknown option '$1' (try --help)" >&2; exit 2; fi
root="$(cd "$(dirname "$0")/.." && pwd)"
meshes=(armadillo.off refined_elephant.off)
tarball=""
for candidate in /usr/share/doc/libcgal-dev/data.tar.gz /usr/share/doc/libcgal-demo/data.tar.gz; do
  if [[ -f "$candidate" ]]; then tarball="$candidate"; break; fi
done
if [[ -z "$tarball" ]]; then
  echo "fetch-meshes.sh: CGAL data tarball not found; install libcgal-demo (scripts/install-deps.sh, as root)" >&2
  exit 1
fi
mkdir -p "$root/assets"
for mesh in "${meshes[@]}"; do
  if [[ -s "$root/assets/$mesh" ]]; then continue; fi
  tar -xzOf "$tarball" "data/meshes/$mesh" > "$root/assets/$mesh.tmp"
  mv "$root/assets/$mesh.tmp" "$root/assets/$mesh"
  echo "fetch-meshes.sh: assets/$mesh from $tarball"
done
echo "fetch-meshes.sh: ${meshes[*]} present in assets/"
