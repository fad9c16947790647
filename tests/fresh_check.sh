#!/usr/bin/env bash
# make fresh-check: proves the README's commands on a machine where nothing was installed by
# hand. A minimal Debian 12 root (debootstrap --variant=minbase, cached as a tarball under
# ~/.cache so it is built once) gets a clean clone of HEAD and ../shared beside it, then only
# `make` from apt; everything else must come from the project's own `make` targets. Runs, in
# the root: make test, then make render (a smoke test of the main binary). FRESH_TARGETS
# overrides the list (e.g. FRESH_TARGETS="test run"). KEEP_ROOT=1 keeps the root for
# inspection. Needs root (chroot, mounts); prints how long each step took.
set -euo pipefail

repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
shared=$(realpath "${SHARED:-$repo/../shared}")
suite=bookworm
mirror=http://deb.debian.org/debian
cache=${XDG_CACHE_HOME:-$HOME/.cache}/importance-sampling-renderer
tarball=$cache/debian12-$suite-minbase.tar.gz
targets=${FRESH_TARGETS:-test render}

[ "$(id -u)" = 0 ] || { echo "fresh-check: needs root (chroot and mounts); run it with sudo" >&2; exit 2; }
[ -d "$shared" ] || { echo "fresh-check: $shared not found (SHARED=... names it)" >&2; exit 2; }

steps=()
timed() { # timed LABEL COMMAND...: runs COMMAND, records its wall time under LABEL
  local label=$1 start end
  shift
  echo "== fresh-check: $label"
  start=$(date +%s%N)
  "$@"
  end=$(date +%s%N)
  local tenths=$(((end - start) / 100000000))
  steps+=("$(printf '%-38s %6d.%d s' "$label" $((tenths / 10)) $((tenths % 10)))")
}
report() {
  echo "== fresh-check: step times"
  printf '%s\n' "${steps[@]}"
}

install_host_package() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "ok installed" && return
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$1" >/dev/null
}

# The cached root: debootstrap's minimal base plus the apt sources of a standard install
# (security and point-release updates), nothing else.
build_root_tarball() {
  install_host_package debootstrap
  local staging
  staging=$(mktemp -d)
  debootstrap --variant=minbase "$suite" "$staging" "$mirror" >"$staging.log" 2>&1 || {
    tail -20 "$staging.log" >&2
    rm -rf "$staging" "$staging.log"
    return 1
  }
  cat >"$staging/etc/apt/sources.list" <<EOF
deb $mirror $suite main
deb $mirror $suite-updates main
deb http://deb.debian.org/debian-security $suite-security main
EOF
  rm -rf "$staging"/var/cache/apt/archives/*.deb "$staging"/var/lib/apt/lists/*
  mkdir -p "$cache"
  tar -C "$staging" -czf "$tarball.tmp" .
  mv "$tarball.tmp" "$tarball"
  rm -rf "$staging" "$staging.log"
}

work=$(mktemp -d "${TMPDIR:-/tmp}/fresh-check.XXXXXX")
root=$work/root
cleanup() {
  # The chroot's mounts lived in a private mount namespace and are gone with it, so this
  # removes plain files only.
  if [ -n "${KEEP_ROOT:-}" ]; then echo "fresh-check: root kept at $root"; else rm -rf "$work"; fi
}
trap 'status=$?; report; cleanup; exit $status' EXIT

if [ -f "$tarball" ]; then
  timed "root creation (cached tarball)" true
else
  timed "root creation (debootstrap)" build_root_tarball
fi

unpack_root() {
  mkdir -p "$root"
  tar -C "$root" -xzf "$tarball"
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  # The machine's own network set-up, as a user's machine has it: the site certificate
  # authorities it trusts (an egress proxy's, which npm's registry is reached through here).
  # Debian's ca-certificates, which make deps installs, folds them into the root's bundle.
  if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
    mkdir -p "$root/usr/local/share/ca-certificates"
    cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
  fi
  mkdir -p "$root/work"
  git clone --quiet --no-hardlinks "$repo" "$root/work/main"
  git -C "$root/work/main" checkout --quiet --detach "$(git -C "$repo" rev-parse HEAD)"
  cp -a "$shared" "$root/work/shared"
}
timed "unpack root, clone HEAD, copy shared" unpack_root

# Runs a command in the root with a clean environment, inside a private mount namespace.
in_root() {
  unshare --mount --propagation private /bin/bash -c '
    set -e
    root=$1; shift
    mount -t proc proc "$root/proc"
    mount -t sysfs sys "$root/sys"
    mount --rbind /dev "$root/dev"
    exec chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb REQUIRE_ASSETS=1 \
      PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
      /bin/bash -c "cd /work/main && $*"
  ' in_root "$root" "$@"
}

timed "install make (apt)" in_root \
  'apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends make >/dev/null'
timed "make deps (package installation)" in_root 'make deps'
timed "make build" in_root 'make build'
for target in $targets; do
  timed "make $target" in_root "make $target"
done
echo "== fresh-check: passed (HEAD $(git -C "$repo" rev-parse --short HEAD), targets: $targets)"
