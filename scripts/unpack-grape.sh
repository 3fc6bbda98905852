#!/usr/bin/env bash
# Unpacks the grape point-cloud archive (Luo et al.) into a cache folder, never into the repo.
#   scripts/unpack-grape.sh [ARCHIVE] [DEST]
# ARCHIVE defaults to ../shared/data/grape/grape_points_train.tar.gz (next to the repository),
# DEST to ${XDG_CACHE_HOME:-$HOME/.cache}/cropsight/grape. Prints DEST (which then holds points/).
# Idempotent: an already complete unpack (marker file) is reused.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
archive="${1:-$here/../shared/data/grape/grape_points_train.tar.gz}"
dest="${2:-${XDG_CACHE_HOME:-$HOME/.cache}/cropsight/grape}"
if [[ ! -f "$archive" ]]; then
  echo "unpack-grape: $archive: no such archive" >&2
  exit 2
fi
marker="$dest/.unpacked-$(basename "$archive")"
if [[ -f "$marker" ]]; then
  echo "$dest"
  exit 0
fi
mkdir -p "$dest"
tmp="$(mktemp -d "$dest/.tmp.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
tar -xzf "$archive" -C "$tmp"
# Move the unpacked tree into place only once it is complete (no partial output).
for entry in "$tmp"/*; do
  rm -rf "$dest/$(basename "$entry")"
  mv "$entry" "$dest/"
done
touch "$marker"
echo "$dest"
