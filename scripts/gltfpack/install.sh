#!/bin/sh
# Installs the gltfpack pinned by scripts/gltfpack/package-lock.json into PREFIX
# (default: build/npm-gltfpack), where `crowdbake bench simplify` looks for it next to the
# build's cli/ folder. A separate prefix from the glTF validator's, so neither install
# removes the other. Reinstalls only when the lock file changed.
# Exit status: 0 installed (or already there); 77 node/npm missing or npm ci failed.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
prefix=${1:-$here/../../build/npm-gltfpack}
for tool in node npm; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "skip: '$tool' not found; install Node.js (scripts/install-deps.sh) to run gltfpack" >&2
    exit 77
  fi
done
mkdir -p "$prefix"
if [ -x "$prefix/node_modules/.bin/gltfpack" ] && cmp -s "$here/package-lock.json" "$prefix/package-lock.json"; then
  exit 0
fi
cp "$here/package.json" "$here/package-lock.json" "$prefix/"
if ! npm ci --prefix "$prefix" --no-audit --no-fund --loglevel=error >"$prefix/npm-ci.log" 2>&1; then
  echo "skip: could not install gltfpack into $prefix (is the npm registry reachable?); see $prefix/npm-ci.log" >&2
  rm -f "$prefix/package-lock.json"
  exit 77
fi
