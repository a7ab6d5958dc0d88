#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# One command for every test: installs what is missing, builds, runs the core and element tests.
set -uo pipefail
cd "$(dirname "$0")/.."
bash tests/bootstrap.sh || exit 1

log=$(mktemp)
meson test -C build --print-errorlogs "$@" 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
ok=$(sed -n 's/^Ok: *\([0-9]*\).*/\1/p' "$log" | tail -1)
fail=$(sed -n 's/^Fail: *\([0-9]*\).*/\1/p' "$log" | tail -1)
timeout=$(sed -n 's/^Timeout: *\([0-9]*\).*/\1/p' "$log" | tail -1)
skipped=$(sed -n 's/^Skipped: *\([0-9]*\).*/\1/p' "$log" | tail -1)
rm -f "$log"
echo "tests: ${ok:-0} passed, $(( ${fail:-0} + ${timeout:-0} )) failed, ${skipped:-0} skipped"
if [ "${ok:-0}" -eq 0 ] && [ "$status" -eq 0 ]; then
  echo "no test ran" >&2
  exit 1
fi
exit "$status"
