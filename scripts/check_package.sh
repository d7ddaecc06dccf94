#!/usr/bin/env bash
# Proves the Debian package on a clean Debian 12: bootstraps a minimal
# bookworm root with debootstrap (kept as a pristine base and copied fresh
# for every check), installs the package there with
# `apt-get install ./colmap-gcn_*.deb`, then runs from the installed files
# only: `colmap-gcn gcn_matcher -h`, `colmap gcn_matcher -h` with
# /usr/lib/colmap-gcn first on PATH, `colmap help` (the real COLMAP) and the
# installed demo. Prints each step's time. Needs root and the network.
#   usage: bash scripts/check_package.sh [package.deb]   (default: newest in dist/)
#   WORK=folder (default /var/tmp/colmap-gcn-check), MIRROR=url (default:
#   the Debian mirror of /etc/apt/sources.list*)
set -euo pipefail
cd "$(dirname "$0")/.."
deb="${1:-$(ls -t dist/colmap-gcn_*.deb 2>/dev/null | head -1)}"
[ -f "$deb" ] || { echo "check_package: no package; run scripts/package.sh" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || { echo "check_package: needs root (debootstrap, chroot)" >&2; exit 1; }
work="${WORK:-/var/tmp/colmap-gcn-check}"
base="$work/bookworm-base"
root="$work/root"
mirror="${MIRROR:-$(grep -rhoE '^(URIs:|deb) +https?://[^ ]+' /etc/apt/sources.list /etc/apt/sources.list.d/ 2>/dev/null |
  awk '{print $2}' | grep -m1 '/debian/*$' || true)}"
mirror="${mirror:-http://deb.debian.org/debian}"

step() {  # step <title> <command...>: runs it, prints its time
  local title="$1" start=$SECONDS
  shift
  echo "== $title"
  "$@"
  echo "== $title: ok, $((SECONDS - start)) s"
}
in_root() { chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin \
  DEBIAN_FRONTEND=noninteractive LANG=C.UTF-8 bash -c "$1"; }
cleanup() {
  for mount in "$root/dev/pts" "$root/dev" "$root/proc"; do
    mountpoint -q "$mount" && umount -l "$mount"
  done
  return 0
}
trap cleanup EXIT

command -v debootstrap >/dev/null || step "apt-get install debootstrap" \
  apt-get install -y -qq debootstrap
if [ ! -x "$base/usr/bin/apt-get" ]; then
  rm -rf "$base"
  step "debootstrap bookworm from $mirror" \
    debootstrap --variant=minbase bookworm "$base" "$mirror"
fi
cleanup
rm -rf "$root"
step "fresh copy of the clean root" cp -a "$base" "$root"
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
cp /etc/resolv.conf "$root/etc/resolv.conf"
cp "$deb" "$root/root/"
name="$(basename "$deb")"
step "apt-get install ./$name" in_root \
  "apt-get update -qq && cd /root && apt-get install -y -qq ./$name >/root/apt.log"
step "installed files" in_root "dpkg -L colmap-gcn | grep -v '/doc/colmap-gcn/docs/'"
step "colmap-gcn gcn_matcher -h" in_root "colmap-gcn gcn_matcher -h | head -5"
step "colmap gcn_matcher -h (PATH=/usr/lib/colmap-gcn:\$PATH)" in_root \
  "PATH=/usr/lib/colmap-gcn:\$PATH colmap gcn_matcher -h | head -5"
step "colmap-gcn help (the real COLMAP)" in_root "colmap-gcn help | head -3"
step "installed demo" in_root "cd /root && bash /usr/share/colmap-gcn/demo.sh demo"
echo "check_package: $name installs and runs on a clean Debian 12 root"
