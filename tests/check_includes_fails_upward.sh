#!/usr/bin/env bash
# tools/check-includes passes on the tree and fails on each kind of edge it forbids: an upward
# include (core -> sim), a sideways one between folders of one layer (collide -> constrain), an
# engine header in ui/, and a folder without a layer.
set -euo pipefail
root="$1"
check="$root/tools/check-includes"
"$check" "$root" >/dev/null
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
expect_failure() {  # name, file to append to, line
  rm -rf "$work/tree" && mkdir -p "$work/tree"
  cp -r "$root/engine" "$root/ui" "$root/draw" "$work/tree/"
  mkdir -p "$(dirname "$work/tree/$2")"
  echo "$3" >>"$work/tree/$2"
  if "$check" "$work/tree" 2>"$work/err"; then
    echo "check-includes passed with $1 ($2: $3)" >&2
    exit 1
  fi
  grep -q . "$work/err" || { echo "check-includes failed silently on $1" >&2; exit 1; }
  echo "refused $1: $(head -1 "$work/err")"
}
expect_failure "an upward include" engine/core/types.h '#include "sim/model.h"'
expect_failure "a sideways include" engine/collide/obstacle.h '#include "constrain/constraint_def.h"'
expect_failure "an engine header in ui/" ui/camera.h '#include "core/types.h"'
expect_failure "a folder without a layer" engine/unlayered/part.h '#include "core/types.h"'
