#!/usr/bin/env bash
# Installs the Debian packages mdhd builds with (scripts/run.sh) and, with --test,
# also those its tests, benchmarks and fuzzing use (scripts/test.sh). Idempotent and
# non-interactive: packages already present are not fetched again.
set -euo pipefail
packages=(build-essential cmake pkg-config
  libmodbus-dev libglm-dev nlohmann-json3-dev libcpp-httplib-dev
  libgtest-dev libgmock-dev libbenchmark-dev libsqlite3-dev sqlite3)
if [ "${1:-}" = "--test" ]; then
  # clang: fuzz targets; wrk: the HTTP benchmark; pymodbus: a Modbus peer no one here
  # wrote; systemd and curl: the deploy test; nodejs and chromium: the UI's tests.
  packages+=(clang libclang-rt-14-dev wrk
    python3-pymodbus python3-serial python3-serial-asyncio
    systemd curl nodejs chromium)
elif [ -n "${1:-}" ]; then
  echo "install-deps: unknown argument '$1' (--test or nothing)" >&2
  exit 2
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm (tests only): Debian's package, unless the installed nodejs brings its own
# (NodeSource's nodejs includes npm and conflicts with Debian's npm package).
if [ "${1:-}" = "--test" ]; then
  command -v npm >/dev/null 2>&1 || missing+=(npm)
fi
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  echo "install-deps: installing ${missing[*]}" >&2
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi
