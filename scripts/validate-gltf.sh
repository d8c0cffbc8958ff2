#!/bin/sh
# Validates a .glb/.gltf with the Khronos glTF validator.
#
# Usage: scripts/validate-gltf.sh FILE [--strict]
#
# On first use it installs the validator pinned by scripts/gltf-validator/package-lock.json
# (npm gltf-validator 2.0.0-dev.3.10) into $GLTF_VALIDATOR_PREFIX (default: build/npm);
# later runs reuse it. Prints the error/warning counts and every issue.
# Exit status: 0 clean; 1 errors (with --strict: also warnings); 2 bad usage or unreadable
# file; 77 node/npm missing or the install failed (CTest reports the test as skipped).
set -eu

here=$(cd "$(dirname "$0")" && pwd)
pins="$here/gltf-validator"
prefix=${GLTF_VALIDATOR_PREFIX:-$here/../build/npm}

if [ $# -lt 1 ]; then
  echo "usage: $0 FILE.glb [--strict]" >&2
  exit 2
fi
for tool in node npm; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "skip: '$tool' not found; install Node.js (scripts/install-deps.sh) to validate glTF" >&2
    exit 77
  fi
done

install() {
  # note: reinstall only when the pinned lock file changed (or nothing is installed yet).
  if [ -f "$prefix/node_modules/gltf-validator/package.json" ] &&
     cmp -s "$pins/package-lock.json" "$prefix/package-lock.json"; then
    return 0
  fi
  cp "$pins/package.json" "$pins/package-lock.json" "$prefix/"
  npm ci --prefix "$prefix" --no-audit --no-fund --loglevel=error >"$prefix/npm-ci.log" 2>&1
}

mkdir -p "$prefix"
# note: parallel CTest runs share the prefix; serialise the install where flock exists.
if command -v flock >/dev/null 2>&1; then
  exec 9>"$prefix/.install.lock"
  flock 9
fi
if ! install; then
  echo "skip: could not install gltf-validator into $prefix (npm ci failed; is the npm" \
       "registry reachable?); see $prefix/npm-ci.log" >&2
  rm -f "$prefix/package-lock.json"
  exit 77
fi
if command -v flock >/dev/null 2>&1; then
  flock -u 9
fi

GLTF_VALIDATOR_PREFIX="$prefix" exec node "$pins/validate.mjs" "$@"
