#!/usr/bin/env bash
# Sets up a fresh Debian machine (packages), builds mdhd and starts the service
# on its embedded defaults. Extra arguments go to `mdhd serve`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh release
exec build/bin/mdhd serve "$@"
