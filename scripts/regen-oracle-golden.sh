#!/bin/bash
# Regenerates the interpreter's golden traces in tests/data/gcode-oracle/ with
# LinuxCNC's standalone interpreter rs274 (Debian package linuxcnc-uspace; not
# installed in CI, and it pulls a kernel package: use a throw-away machine).
# Same steps as ../shared/gcode-oracle/run_all.sh, with its harness rs274_trace.py.
# Not run by the tests.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
harness=${MDHD_ORACLE_HARNESS:-$repo/../shared/gcode-oracle/rs274_trace.py}
data=$repo/tests/data/gcode-oracle
command -v rs274 >/dev/null || { echo "rs274 not found (apt-get install linuxcnc-uspace)" >&2; exit 1; }
[ -f "$harness" ] || { echo "harness not found: $harness" >&2; exit 1; }
trace() {  # dir file extra-args...
  local dir=$1 file=$2; shift 2
  local out=$data/$dir/${file%.ngc}.jsonl
  # exit 2 = rs274 rejected the program (an error record is written): expected for some
  python3 "$harness" "$@" "$data/$dir/$file" -o "$out" || [ $? -eq 2 ]
  echo "$dir/$file: $(grep -cE '"type":"(rapid|feed|arc|probe)"' "$out") motions"
}
for f in $(cd "$data/programs" && ls [0-9]*.ngc); do
  trace programs "$f" -t "$data/programs/tools.tbl"
done
for f in $(cd "$data/corpus" && ls *.ngc); do
  case $f in
    mmount.ngc) trace corpus "$f" -t "$data/corpus/mmount.tbl" --tool-units inch ;;
    *) trace corpus "$f" -t "$data/corpus/tools.tbl" ;;
  esac
done
