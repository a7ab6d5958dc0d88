#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Measures the README's set-up figures and writes them into README.md (between its "setup-figures" markers),
# so that no figure there is copied by hand. As root, on a Debian machine that can reach a Debian mirror:
#   demo       a fresh `debootstrap --variant=minbase bookworm` chroot; the work tree copied in; the README's
#              demo command (examples/run-demo.sh) run there
#   tests      then the README's test command (tests/run-tests.sh) in the same chroot
#   sanitized  then tests/run-sanitized.sh in the same chroot
#   debian13   tests/run-debian13.sh into a fresh Debian 13 chroot of its own
# Each part records its packages, bytes downloaded, disk used, build steps and time; the parts given as
# arguments are measured (default: all four, about an hour on a 2-core machine), the others keep their
# figures in docs/setup-figures.json. `tests` is measured after the demo and `sanitized` after both, so asking
# for either measures what comes before it too (in a fresh chroot). tests/check_setup_figures.py (the suite's
# `setup-figures` test) checks what can be checked cheaply: the package lists' sizes and the build steps,
# against the tree as it is now; during a measurement it says SKIPPED (COLORTRACK_MEASURING_SETUP=1), so a
# drift it would report does not stop the measurement that mends it.
#
# Settings (environment): COLORTRACK_MEASURE_ROOT (default /var/tmp/colortrack-measure: its chroots are made
# afresh), DEBIAN_MIRROR (default http://deb.debian.org/debian).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
base=${COLORTRACK_MEASURE_ROOT:-/var/tmp/colortrack-measure}
root=$base/bookworm
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
src=/src/colortrack
results=$base/figures.json
export COLORTRACK_MEASURING_SETUP=1
# shellcheck source=tests/chroot-lib.sh
source "$repo/tests/chroot-lib.sh"
cannot() {
  echo "measure-setup.sh: cannot make a chroot here: $*" >&2
  exit 77
}
[ "$(id -u)" -eq 0 ] || cannot "needs root (debootstrap, mount, chroot)"
parts=("$@")
[ ${#parts[@]} -gt 0 ] || parts=(demo tests sanitized debian13)
wants() { [[ " ${parts[*]} " == *" $1 "* ]]; }
# What comes before a part is measured with it: the figures of `tests` are what it adds after the demo.
! wants sanitized || parts+=(tests)
! wants tests || parts+=(demo)
# The tree as it is now, named once (commits made while it is measured are not what was measured).
commit=$(git -c safe.directory="$repo" -C "$repo" describe --always --dirty)

# (0 for a chroot not made yet.)
packages_in() {
  [ -x "$1/usr/bin/dpkg-query" ] || { echo 0; return; }
  chroot "$1" dpkg-query -W -f='${Status}\n' | grep -c "install ok installed"
}
kib_of() { if [ -d "$1" ]; then du -sx --block-size=1K "$1" | cut -f1; else echo 0; fi; }
# Bytes of .deb files apt has downloaded into the chroot's cache so far.
downloaded_kib() {
  [ -d "$1/var/cache/apt/archives" ] || { echo 0; return; }
  find "$1/var/cache/apt/archives" -name '*.deb' -printf '%s\n' | awk '{ s += $1 } END { print int(s / 1024) }'
}

# measure PART CHROOT COMMAND...: runs COMMAND, records PART's figures in $results.
measure() {
  local part=$1 where=$2 start packages kib download
  shift 2
  packages=$(packages_in "$where")
  kib=$(kib_of "$where")
  download=$(downloaded_kib "$where")
  start=$SECONDS
  echo "== measuring $part: $*"
  if ! "$@" 2>&1 | while IFS= read -r line; do printf '%(%s)T %s\n' -1 "$line"; done >"$base/$part.log"; then
    echo "measure-setup.sh: $part failed; see $base/$part.log" >&2
    exit 1
  fi
  python3 "$repo/tests/check_setup_figures.py" record "$results" "$part" \
    --seconds $((SECONDS - start)) --log "$base/$part.log" \
    --packages $(($(packages_in "$where") - packages)) --disk-kib $(($(kib_of "$where") - kib)) \
    --download-kib $(($(downloaded_kib "$where") - download)) --commit "$commit"
}

mkdir -p "$base"
# The parts not measured keep the figures the project has.
[ ! -f "$repo/docs/setup-figures.json" ] || cp "$repo/docs/setup-figures.json" "$results"
if wants demo; then
  unmount_under "$root"
  echo "== debootstrap bookworm into $root"
  debootstrap_into_root bookworm
  # What a newcomer has before cloning (not counted).
  chroot "$root" apt-get install -y -q --no-install-recommends git ca-certificates
fi
if wants demo || wants tests || wants sanitized; then
  trap chroot_unmount EXIT
  chroot_mount_all
  copy_work_tree "$repo"
  chroot_trust_host_ca
  ! wants demo || measure demo "$root" in_chroot "examples/run-demo.sh"
  ! wants tests || measure tests "$root" in_chroot "tests/run-tests.sh"
  ! wants sanitized || measure sanitized "$root" in_chroot "tests/run-sanitized.sh"
  chroot_unmount
fi
if wants debian13; then
  unmount_under "$base/trixie"
  rm -rf --one-file-system "$base/trixie"
  measure debian13 "$base/trixie" env COLORTRACK_DEBIAN13_CHROOT="$base/trixie" bash "$repo/tests/run-debian13.sh"
fi
python3 "$repo/tests/check_setup_figures.py" write "$results" "$repo/README.md"
echo "== README.md's set-up figures written from $results"
