#!/usr/bin/env bash
# Configures and builds one flavour of mdhd: scripts/build.sh [release|asan] [extra cmake args...]
# release -> build/, asan -> build-asan/ (AddressSanitizer + UndefinedBehaviorSanitizer).
set -euo pipefail
cd "$(dirname "$0")/.."
flavour=${1:-release}
shift || true
case "$flavour" in
  # -g1 (line tables only): enough for stack traces, much cheaper to compile and link.
  release) dir=build; flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG") ;;
  # -O1 keeps sanitized tests fast; no NDEBUG, so debug-only invariant checks run.
  asan) dir=build-asan; flags=(-DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" -DMDHD_SANITIZE=ON -DMDHD_BENCH=OFF) ;;
  *) echo "build.sh: unknown flavour '$flavour' (release|asan)" >&2; exit 2 ;;
esac
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B "$dir" -DMDHD_WERROR=ON "${flags[@]}" "$@" >/dev/null
cmake --build "$dir" -j "$jobs"
