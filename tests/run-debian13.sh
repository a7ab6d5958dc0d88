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

# Unmounts whatever is mounted under $1 (a run or a debootstrap killed before it could clean up), deepest
# first, so that nothing under it is removed through a mount.
unmount_under() {
  local dir m
  dir=$(realpath -m "$1")
  awk -v d="$dir" '$2 == d || index($2, d "/") == 1 { print $2 }' /proc/mounts | sort -r |
    while read -r m; do umount "$m" 2>/dev/null || umount -l "$m"; done
}
unmount_under "$root"
unmount_under "$root.partial"

# 1. The chroot.
if [ ! -f "$root/etc/debian_version" ] || ! grep -q '^13' "$root/etc/debian_version" ||
  [ ! -x "$root/usr/bin/apt-get" ]; then
  begin "debootstrap trixie into $root"
  command -v debootstrap >/dev/null || {
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap || cannot "debootstrap cannot be installed"
  }
  # Into a temporary directory first: a debootstrap cut short leaves no half chroot under $root.
  rm -rf "$root.partial"
  mkdir -p "$(dirname "$root")"
  debootstrap --variant=minbase trixie "$root.partial" "$mirror" ||
    cannot "debootstrap trixie from $mirror failed (no access to a Debian mirror? DEBIAN_MIRROR names another)"
  rm -rf "$root"
  mv "$root.partial" "$root"
  end "debootstrap"
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"

# Mounts, undone on any exit (failure and interruption too).
mounted=()
cleanup() {
  local status=$? i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount "${mounted[i]}" 2>/dev/null || umount -l "${mounted[i]}" || echo "could not unmount ${mounted[i]}" >&2
  done
  summary
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM
mount_in() {  # mount_in TARGET MOUNT-ARGS...
  local target=$root$1
  shift
  mkdir -p "$target"
  mount "$@" "$target" || cannot "mounting $1 in the chroot is not allowed"
  mounted+=("$target")
}
mount_in /proc -t proc proc
mount_in /sys -t sysfs sysfs
mount_in /dev --bind /dev
mount_in /dev/pts --bind /dev/pts
mount_in /dev/shm -t tmpfs -o mode=1777,nosuid,nodev shm

# 2. The work tree.
begin "copy $repo to $root$src"
mkdir -p "$root$src"
if [ "${COLORTRACK_DEBIAN13_CLEAN:-0}" = 1 ]; then
  rm -rf "$root$src/build"
fi
# Into a staging directory, then only the files whose content differs are copied over (with the time of the
# copy, so that ninja rebuilds what changed: the work tree's own times may be older than the kept build's),
# and files no longer in the work tree are removed. Nothing under build*/ (git ignores them) is touched.
stage="$root/src/.incoming"
dest="$root$src"
rm -rf "$stage"
mkdir -p "$stage"
git -C "$repo" ls-files -z --cached --others --exclude-standard |
  tar -C "$repo" --no-recursion --ignore-failed-read --null -cf - -T - | tar -xf - -C "$stage"
changed=0
while IFS= read -r -d '' f; do
  if ! cmp -s "$stage/$f" "$dest/$f"; then
    mkdir -p "$(dirname "$dest/$f")"
    rm -f "$dest/$f"
    cp -P --preserve=mode "$stage/$f" "$dest/$f"
    changed=$((changed + 1))
  fi
done < <(cd "$stage" && find . ! -type d -print0)
while IFS= read -r -d '' f; do
  [ -e "$stage/$f" ] || [ -L "$stage/$f" ] || rm -f "$dest/$f"
done < <(cd "$dest" && find . -path './build*' -prune -o ! -type d -print0)
rm -rf "$stage"
echo "$changed files changed"
end "copy"

# The host's certificate authorities for npm's HTTPS requests from inside the chroot (tests/bootstrap.sh
# installs node-mavlink): the host may reach the registry through a proxy whose CA only the host trusts.
# apt in the chroot uses the Debian mirror over HTTP and needs none of this.
ca_env=()
host_ca=${NODE_EXTRA_CA_CERTS:-/etc/ssl/certs/ca-certificates.crt}
if [ -r "$host_ca" ]; then
  cp "$host_ca" "$root/etc/colortrack-host-ca.crt"
  ca_env=(NODE_EXTRA_CA_CERTS=/etc/colortrack-host-ca.crt npm_config_cafile=/etc/colortrack-host-ca.crt)
fi

in_chroot() {
  chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 \
    TERM="${TERM:-dumb}" CI="${CI:-}" COLORTRACK_REQUIRE_NODE_MAVLINK="${COLORTRACK_REQUIRE_NODE_MAVLINK:-0}" \
    "${ca_env[@]}" /bin/bash -c "cd $src && $*"
}

# 3. Packages and build, then the tests.
begin "tests/bootstrap.sh (packages, build)"
in_chroot "bash tests/bootstrap.sh 2>&1 | while IFS= read -r line; do printf '%(%T)T %s\n' -1 \"\$line\"; done; exit \${PIPESTATUS[0]}"
end "packages and build"
begin "tests/run-tests.sh $*"
args=""
[ $# -eq 0 ] || args=$(printf ' %q' "$@")
in_chroot "bash tests/run-tests.sh$args"
end "tests"
