#!/usr/bin/env bash
# Sets up a fresh Debian machine (packages), builds mdhd twice (optimised, and
# with AddressSanitizer + UndefinedBehaviorSanitizer) and runs every test in both.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --test
jobs=$(nproc 2>/dev/null || echo 2)
# The browser UI's test tools (web/package-lock.json: playwright-core, no browser download).
npm ci --prefix web --no-audit --no-fund --loglevel=error >/dev/null

echo "== build (RelWithDebInfo, warnings as errors)"
bash scripts/build.sh release
echo "== tests"
ctest --test-dir build -j "$jobs" --output-on-failure --timeout 600

echo "== build (ASan + UBSan)"
bash scripts/build.sh asan
echo "== tests under ASan + UBSan"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -j "$jobs" --output-on-failure --timeout 900 -LE bench
