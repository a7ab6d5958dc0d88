#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# The project's tests (tests/run-tests.sh) on Debian 13 (trixie, GStreamer 1.26: the analytics meta is built
# and tested there, see gst/colortrack/analytics-meta.h), in a chroot, from any Debian machine where we are root:
#   1. debootstrap --variant=minbase trixie into the chroot if it has no Debian 13 yet (debootstrap is
#      installed if missing);
#   2. copies this work tree (git's tracked and untracked files, not ignored ones such as build directories)
#      to /src/colortrack in the chroot, keeping the build/ a previous run left there (only files whose
#      content changed are copied, so that build/ rebuilds exactly those);
#   3. inside: tests/bootstrap.sh (installs the packages, builds), then tests/run-tests.sh "$@".
# /proc, /sys, /dev, /dev/pts and /dev/shm are mounted in the chroot for the run and unmounted at the end,
# whatever happens. Each phase's time is printed at the end.
#
# Exit code 77 when this machine cannot make the chroot at all (not root, debootstrap cannot reach a Debian
# mirror, mounting is not allowed): .ci/run reports that as skipped. Anything else that fails is a failure.
#
# Settings (environment): COLORTRACK_DEBIAN13_CHROOT (default /var/tmp/colortrack-debian13),
# DEBIAN_MIRROR (default http://deb.debian.org/debian), COLORTRACK_DEBIAN13_CLEAN=1 to remove the chroot's
# build/ first (a build from nothing).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
root=${COLORTRACK_DEBIAN13_CHROOT:-/var/tmp/colortrack-debian13}
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
src=/src/colortrack
# shellcheck source=tests/chroot-lib.sh
source "$repo/tests/chroot-lib.sh"

# This machine cannot run the Debian 13 tests: say why and exit 77.
cannot() {
  echo "run-debian13.sh: cannot make a Debian 13 chroot here: $*" >&2
  exit 77
}
[ "$(id -u)" -eq 0 ] || cannot "needs root (debootstrap, mount, chroot)"

phases=()
phase_start=0
begin() {
  phase_start=$SECONDS
  echo "== $1"
}
end() { phases+=("$(printf '%-28s %4d s' "$1" $((SECONDS - phase_start)))"); }
summary() {
  echo "== Debian 13 run: phases"
  local p
  for p in "${phases[@]}"; do echo "   $p"; done
}

unmount_under "$root"
unmount_under "$root.partial"

# 1. The chroot.
if [ ! -f "$root/etc/debian_version" ] || ! grep -q '^13' "$root/etc/debian_version" ||
  [ ! -x "$root/usr/bin/apt-get" ]; then
  begin "debootstrap trixie into $root"
  debootstrap_into_root trixie
  end "debootstrap"
fi

# Mounts, undone on any exit (failure and interruption too).
cleanup() {
  local status=$?
  chroot_unmount
  summary
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM
chroot_mount_all

# 2. The work tree.
begin "copy $repo to $root$src"
if [ "${COLORTRACK_DEBIAN13_CLEAN:-0}" = 1 ]; then
  rm -rf "$root$src/build"
fi
copy_work_tree "$repo"
end "copy"

chroot_trust_host_ca

# 3. Packages and build, then the tests.
begin "tests/bootstrap.sh (packages, build)"
in_chroot "bash tests/bootstrap.sh 2>&1 | while IFS= read -r line; do printf '%(%T)T %s\n' -1 \"\$line\"; done; exit \${PIPESTATUS[0]}"
end "packages and build"
begin "tests/run-tests.sh $*"
args=""
[ $# -eq 0 ] || args=$(printf ' %q' "$@")
in_chroot "bash tests/run-tests.sh$args"
end "tests"
