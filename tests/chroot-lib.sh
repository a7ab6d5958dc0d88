# SPDX-License-Identifier: LGPL-2.1-or-later
# Shell functions for running the project in a Debian chroot, sourced by tests/run-debian13.sh (the tests on
# Debian 13) and tests/measure-setup.sh (the README's set-up figures on a fresh Debian 12). The caller
# sets `root` (the chroot), `mirror` (a Debian mirror) and `src` (the work tree's place inside the chroot),
# and defines `cannot MESSAGE` (exits 77: this machine cannot make a chroot).

# Unmounts whatever is mounted under $1 (a run or a debootstrap killed before it could clean up), deepest
# first, so that nothing under it is removed through a mount.
unmount_under() {
  local dir m
  dir=$(realpath -m "$1")
  awk -v d="$dir" '$2 == d || index($2, d "/") == 1 { print $2 }' /proc/mounts | sort -r |
    while read -r m; do umount "$m" 2>/dev/null || umount -l "$m"; done
}

# debootstrap --variant=minbase SUITE into $root, through $root.partial so that a debootstrap cut short
# leaves no half chroot under $root (debootstrap is installed if missing).
debootstrap_into_root() {
  local suite=$1
  command -v debootstrap >/dev/null || {
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap || cannot "debootstrap cannot be installed"
  }
  # (Nothing is removed through a mount a killed run left: unmounted first, and rm stays on this filesystem.)
  unmount_under "$root.partial"
  rm -rf --one-file-system "$root.partial"
  mkdir -p "$(dirname "$root")"
  debootstrap --variant=minbase "$suite" "$root.partial" "$mirror" ||
    cannot "debootstrap $suite from $mirror failed (no access to a Debian mirror? DEBIAN_MIRROR names another)"
  unmount_under "$root"
  rm -rf --one-file-system "$root"
  mv "$root.partial" "$root"
}

# Mounts /proc, /sys, /dev, /dev/pts and /dev/shm in $root; chroot_unmount undoes them (call it on exit).
chroot_mounts=()
chroot_mount() {  # chroot_mount TARGET MOUNT-ARGS...
  local where=$1 target=$root$1
  shift
  mkdir -p "$target"
  mount "$@" "$target" || cannot "mounting $where in the chroot is not allowed"
  chroot_mounts+=("$target")
}
chroot_mount_all() {
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  # A bookworm minbase has no /etc/hosts (a machine has one): without it "localhost" does not resolve, and
  # selenium cannot reach the chromedriver it started.
  [ -e "$root/etc/hosts" ] || printf '127.0.0.1\tlocalhost\n::1\t\tlocalhost ip6-localhost ip6-loopback\n' >"$root/etc/hosts"
  chroot_mount /proc -t proc proc
  chroot_mount /sys -t sysfs sysfs
  chroot_mount /dev --bind /dev
  chroot_mount /dev/pts --bind /dev/pts
  chroot_mount /dev/shm -t tmpfs -o mode=1777,nosuid,nodev shm
}
chroot_unmount() {
  local i
  for ((i = ${#chroot_mounts[@]} - 1; i >= 0; i--)); do
    umount "${chroot_mounts[i]}" 2>/dev/null || umount -l "${chroot_mounts[i]}" ||
      echo "could not unmount ${chroot_mounts[i]}" >&2
  done
  chroot_mounts=()
}

# Copies the work tree $1 (git's tracked and untracked files, not ignored ones such as build directories) to
# $root$src, keeping the build/ a previous run left there. Through a staging directory, then only the files
# whose content differs are copied over (with the time of the copy, so that ninja rebuilds what changed: the
# work tree's own times may be older than the kept build's), and files no longer in the work tree are
# removed. Nothing under build*/ is touched.
copy_work_tree() {
  local repo=$1 stage="$root/src/.incoming" dest="$root$src" changed=0 f
  mkdir -p "$dest"
  rm -rf "$stage"
  mkdir -p "$stage"
  git -C "$repo" ls-files -z --cached --others --exclude-standard |
    tar -C "$repo" --no-recursion --ignore-failed-read --null -cf - -T - | tar -xf - -C "$stage"
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
}

# The host's certificate authorities for npm's HTTPS requests from inside the chroot (tests/bootstrap.sh
# installs node-mavlink): the host may reach the registry through a proxy whose CA only the host trusts.
# apt in the chroot uses the Debian mirror over HTTP and needs none of this.
chroot_ca_env=()
chroot_trust_host_ca() {
  local host_ca=${NODE_EXTRA_CA_CERTS:-/etc/ssl/certs/ca-certificates.crt}
  if [ -r "$host_ca" ]; then
    cp "$host_ca" "$root/etc/colortrack-host-ca.crt"
    chroot_ca_env=(NODE_EXTRA_CA_CERTS=/etc/colortrack-host-ca.crt npm_config_cafile=/etc/colortrack-host-ca.crt)
  fi
}

# Runs a shell command line in the chroot, in $src, with a clean environment.
in_chroot() {
  chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 \
    TERM="${TERM:-dumb}" CI="${CI:-}" COLORTRACK_REQUIRE_NODE_MAVLINK="${COLORTRACK_REQUIRE_NODE_MAVLINK:-0}" \
    COLORTRACK_REQUIRE_BROWSER="${COLORTRACK_REQUIRE_BROWSER:-0}" \
    COLORTRACK_MEASURING_SETUP="${COLORTRACK_MEASURING_SETUP:-}" \
    "${chroot_ca_env[@]}" /bin/bash -c "cd $src && $*"
}
