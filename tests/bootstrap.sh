#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Installs the Debian packages the project needs (only those missing) and builds it into build/.
# Used by the README's two commands:
#   tests/bootstrap.sh demo   (examples/run-demo.sh) the demo's packages; builds the plugin and the demo only
#   tests/bootstrap.sh [all]  (tests/run-tests.sh)   every package; builds everything (tests, benchmarks,
#                             examples, the evaluation tool)
# The demo's list is the smaller one, so a first demo run installs and builds less; the test command then
# adds the rest (and turns tests and benchmarks on in a build/ the demo configured without them).
set -euo pipefail
cd "$(dirname "$0")/.."

mode="${1:-all}"
case "$mode" in
  demo | all) ;;
  *)
    echo "usage: $0 [demo|all]" >&2
    exit 2
    ;;
esac

# Building the plugin and the demo, and running the demo on the built-in scene (videoconvert and appsrc from
# -base; jpegenc, avimux and v4l2src from -good).
demo_packages=(
  g++ meson ninja-build pkg-config
  libgstreamer1.0-dev libgstreamer-plugins-base1.0-dev gstreamer1.0-plugins-base gstreamer1.0-plugins-good
  gstreamer1.0-x libopencv-dev libeigen3-dev libserialport-dev libpaho-mqtt-dev nlohmann-json3-dev
)
# The tests, benchmarks and examples on top: gst-inspect-1.0, cvtracker (-bad and -opencv) for the
# evaluation, GoogleTest, gst-rtsp-server for the RTSP test, PyGObject and GStreamer's Python overrides
# (python3-gst-1.0: threshold mode's objects list) for the Python example, the mosquitto
# broker the trackpublish tests start on loopback, paho-mqtt for the Python MQTT consumer example, node and
# npm for node-mavlink (the MAVLink tests' independent implementation, see below), Universal Ctags for the
# size-limit check (tests/check_limits.py), locales for glibc's locale sources (core-settings-locale builds a
# comma-decimal locale from them), chromium, its driver and selenium for colortrack-studio's browser test
# (tests/studio/check_studio_browser.py).
test_packages=(
  gstreamer1.0-tools gstreamer1.0-plugins-bad gstreamer1.0-opencv libgtest-dev libgstrtspserver-1.0-dev
  python3-gi python3-gst-1.0 gir1.2-gstreamer-1.0 gir1.2-gst-plugins-base-1.0 mosquitto openssl
  python3-paho-mqtt universal-ctags locales
  nodejs
  chromium chromium-driver python3-selenium
)
packages=("${demo_packages[@]}")
[ "$mode" = demo ] || packages+=("${test_packages[@]}")

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
sudo=""
[ "$(id -u)" -eq 0 ] || sudo=sudo
updated=false
install_missing() {
  local missing=() p
  for p in "$@"; do installed "$p" || missing+=("$p"); done
  [ ${#missing[@]} -gt 0 ] || return 0
  echo "== installing: ${missing[*]}"
  $updated || $sudo apt-get update -q
  updated=true
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
}
install_missing "${packages[@]}"

# GStreamer 1.24 and newer (Debian 13): the analytics library's headers come with -bad's development package,
# and the plugin then also attaches the analytics meta (gst/colortrack/analytics-meta.h). Debian 12's GStreamer 1.22 has
# no analytics library: nothing to add there. A build/ configured before the package came is configured again
# so that meson finds it.
analytics_added=false
if dpkg --compare-versions "$(dpkg-query -W -f='${Version}' libgstreamer1.0-dev)" ge 1.24 &&
  ! installed libgstreamer-plugins-bad1.0-dev; then
  install_missing libgstreamer-plugins-bad1.0-dev
  analytics_added=true
fi
if $analytics_added && [ -f build/build.ninja ]; then
  meson setup --reconfigure build
fi

# node-mavlink, pinned by tests/mavlink/package-lock.json: the MAVLink tests check robotctl's frames against
# it. Installed once (npm ci); the tests report "skipped" where it is missing.
# npm comes with Node.js packaged elsewhere (NodeSource's nodejs conflicts with Debian's npm package), so
# Debian's npm is installed only when there is no npm at all.
if [ "$mode" = all ] && ! command -v npm >/dev/null; then
  install_missing npm
fi
# (A file is tested, not the directory: the Debian 13 run's copy removes a stale tree's files, not its
# directories.)
# Without the npm registry (an offline machine) the tests still run: the MAVLink oracle tests then say
# SKIPPED. CI sets COLORTRACK_REQUIRE_NODE_MAVLINK=1 so that they are never skipped there.
if [ "$mode" = all ] && [ ! -f tests/mavlink/node_modules/node-mavlink/package.json ]; then
  echo "== installing node-mavlink for the MAVLink tests (npm ci in tests/mavlink)"
  # An unreachable registry is found in seconds (npm ci alone retries for about 70 s).
  if ! timeout 15 npm view node-mavlink version --fetch-retries=0 --fetch-timeout=10000 >/dev/null 2>&1; then
    echo "== the npm registry ($(npm config get registry 2>/dev/null)) does not answer within 15 s"
    npm_reachable=false
  else
    npm_reachable=true
  fi
  if ! $npm_reachable || ! (cd tests/mavlink && npm ci --no-audit --no-fund); then
    [ "${COLORTRACK_REQUIRE_NODE_MAVLINK:-0}" = 1 ] && exit 1
    echo "== WARNING: node-mavlink could not be installed (is the npm registry reachable?): the MAVLink" \
      "byte-for-byte checks against node-mavlink will be SKIPPED"
  fi
fi

# The value of a boolean build option of build/ ("true" or "false").
option_value() {
  meson introspect build --buildoptions |
    python3 -c 'import json, sys; print(str(next(o["value"] for o in json.load(sys.stdin) if o["name"] == sys.argv[1])).lower())' "$1"
}

if [ "$mode" = demo ]; then
  if [ ! -f build/build.ninja ]; then
    meson setup build -Dtests=false -Dbenchmarks=false
  fi
  meson compile -C build gstcolortrack colortrack-demo
else
  if [ ! -f build/build.ninja ]; then
    meson setup build
  else
    off=()
    for option in tests benchmarks examples; do
      [ "$(option_value "$option")" = true ] || off+=("-D$option=true")
    done
    if [ ${#off[@]} -gt 0 ]; then
      echo "== build/ has ${off[*]/%=true/=false}: turning it on"
      meson configure build "${off[@]}"
    fi
  fi
  ninja -C build
fi
