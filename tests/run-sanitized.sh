#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# The core and element tests again, built with AddressSanitizer and UndefinedBehaviorSanitizer in a second
# build directory (build-asan/), so memory and UB errors fail CI. Run by .ci/run after the README's test
# command (which installs the packages). The examples suite is left out: python3 cannot load an ASan-built
# plugin.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build-asan/build.ninja ]; then
  meson setup build-asan -Db_sanitize=address,undefined -Db_lundef=false -Dbuildtype=debugoptimized
fi
ninja -C build-asan
# GStreamer's plugin scanner is not sanitized and cannot load the plugin: scan in-process. Leaks are GLib's
# and GStreamer's type system's by design; memory errors and UB are what this run is for.
export GST_REGISTRY_FORK=no
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
meson test -C build-asan --print-errorlogs --suite core --suite robot --suite gst --suite eval
