#!/usr/bin/env bash
# Run every example lesson (examples/lesson*.rs) and the demos headless, each as
# `cargo run --release --example NAME` in an empty temporary directory, and fail if one
# exits with an error or does not write NAME.png there (a PNG file, not empty).
#
#   bash .ci/examples.sh            # all of them
#   bash .ci/examples.sh bunny cube # only these
#
# The examples are built once first (one cargo call), so the runs only run them.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

if [ "$#" -gt 0 ]; then
  names=("$@")
else
  names=()
  for f in examples/lesson*.rs; do
    names+=("$(basename "$f" .rs)")
  done
  names+=(bunny cube hidden_line oled painter scene textured fog)
fi

build_args=()
for name in "${names[@]}"; do
  build_args+=(--example "$name")
done
cargo build --quiet --release "${build_args[@]}"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failed=()
for name in "${names[@]}"; do
  dir="$tmp/$name"
  mkdir "$dir"
  echo "== $name"
  if ! (cd "$dir" && cargo run --quiet --release --manifest-path "$root/Cargo.toml" --example "$name"); then
    echo "FAILED: $name exited with an error"
    failed+=("$name")
    continue
  fi
  png="$dir/$name.png"
  if [ ! -s "$png" ] || [ "$(head -c 4 "$png" | tail -c 3)" != "PNG" ]; then
    echo "FAILED: $name did not write $name.png"
    failed+=("$name")
  fi
done

if [ "${#failed[@]}" -gt 0 ]; then
  echo "examples failed: ${failed[*]}"
  exit 1
fi
echo "examples: ${#names[@]} ran, each wrote its PNG"
