#!/usr/bin/env bash
# Clean-checkout `make test` time of one or more revisions, one after the other, each in a fresh
# worktree with an empty ccache (the build-time criterion; run on an otherwise idle machine).
#   tools/build-time.sh REV [REV ...]    -> one line per revision: wall, user and system seconds
set -euo pipefail
repo=$(git rev-parse --show-toplevel)
for rev in "$@"; do
  dir=$(mktemp -d)/tree
  git -C "$repo" worktree add -q --detach "$dir" "$rev"
  cache=$(mktemp -d)
  log=$(mktemp)
  (cd "$dir" && CCACHE_DIR=$cache /usr/bin/time -o "$log.time" -f "$rev make test: %e s wall, %U s user, %S s sys" \
     make test > "$log" 2>&1) || echo "$rev: make test failed (log $log)"
  cat "$log.time"; grep -E "tests passed|Total Test time" "$log" || true
  rm -rf "$cache"; git -C "$repo" worktree remove --force "$dir"
done
