#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# One command for the demo: installs what the demo needs (only what is missing), builds the plugin and the
# demo, then runs colortrack on the built-in synthetic scene (or on the device / URL / file given as
# argument) and writes an annotated video.
#
# The demo runs in the directory this script was started from, so relative paths given to it (an input
# file, --output, --template, --robot-output, --robot-log) and its default outputs (colortrack-demo.avi,
# colortrack-demo-robot.txt, colortrack-demo-robot.log) are the caller's, not the project's.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/tests/bootstrap.sh" demo
export GST_PLUGIN_PATH="$root/build/gst${GST_PLUGIN_PATH:+:$GST_PLUGIN_PATH}"
exec "$root/build/examples/colortrack-demo" "$@"
