#!/usr/bin/env bash
# One command for the demo: installs what is missing, builds, then runs colortrack on the built-in
# synthetic scene (or on the device / URL / file given as argument) and writes an annotated video.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tests/bootstrap.sh
export GST_PLUGIN_PATH="$PWD/build/gst${GST_PLUGIN_PATH:+:$GST_PLUGIN_PATH}"
exec ./build/examples/colortrack-demo "$@"
