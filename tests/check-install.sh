#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# The install test (meson test install): `meson install --destdir` puts the build into a staging root, and
# gst-inspect-1.0 must find colortrack, robotctl and trackpublish there, loaded from the staged file: GST_PLUGIN_PATH into
# the staging root, no system plugin directory, a private registry.
#   check-install.sh BUILD_DIR PLUGIN_DIR INCLUDE_DIR GST_INSPECT BIN_DIR
# PLUGIN_DIR, INCLUDE_DIR and BIN_DIR are the absolute install paths meson computed (prefix included).
set -euo pipefail
build="$1" plugin_dir="$2" include_dir="$3" inspect="$4" bin_dir="$5"
stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT

meson install -C "$build" --no-rebuild --quiet --destdir "$stage"

fail() {
  echo "FAIL: $*" >&2
  exit 1
}
plugin="$stage$plugin_dir/libgstcolortrack.so"
[ -f "$plugin" ] || fail "no plugin at $plugin; staged files: $(cd "$stage" && find . -type f | tr '\n' ' ')"
[ -f "$stage$include_dir/colortrack/colortrack-meta.h" ] || fail "no header under $stage$include_dir"
# colortrack-studio looks for its page and modules beside it, then in ../share/colortrack-studio.
studio="$stage$bin_dir/colortrack-studio"
[ -x "$studio" ] || fail "no executable colortrack-studio at $studio"
for part in studio.html studio_pipeline.py studio_server.py; do
  [ -f "$(dirname "$studio")/../share/colortrack-studio/$part" ] ||
    fail "colortrack-studio's $part is not in $(dirname "$studio")/../share/colortrack-studio"
done
# It starts from there: its usage (the modules imported, GStreamer not started).
"$studio" --help >/dev/null || fail "the installed colortrack-studio does not start"
echo "ok: colortrack-studio, its page and its modules"

unset GST_PLUGIN_PATH GST_PLUGIN_SYSTEM_PATH
export GST_PLUGIN_PATH_1_0="$stage$plugin_dir"
export GST_PLUGIN_SYSTEM_PATH_1_0="$stage/no-system-plugins"
export GST_REGISTRY_1_0="$stage/registry.bin"
for element in colortrack robotctl trackpublish; do
  out="$("$inspect" "$element" 2>&1)" || fail "gst-inspect-1.0 $element found nothing in $GST_PLUGIN_PATH_1_0: $out"
  filename="$(printf '%s\n' "$out" | sed -n 's/^ *Filename *//p' | head -1)"
  [ "$filename" = "$plugin" ] || fail "gst-inspect-1.0 $element loaded '$filename', not the staged $plugin"
  echo "ok: $element from $filename"
done
# The plugin's origin is a URL (meson option package-origin; by default the clone's web address or the
# source tree as file://), as gst-inspect and packagers expect.
origin="$("$inspect" colortrack | sed -n 's/^ *Origin URL *//p' | head -1)"
[[ "$origin" =~ ^(https?|file)://[^[:space:]]+$ ]] || fail "the plugin's Origin URL is not a URL: '$origin'"
echo "ok: origin $origin"
