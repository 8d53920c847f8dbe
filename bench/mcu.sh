#!/usr/bin/env bash
# Instruction counts of zraster on the Cortex-M4F (thumbv7em) and Cortex-M0+ (thumbv6m)
# instruction sets, under QEMU's mps2-an386 board with -icount shift=0 (exact and
# repeatable). Needs qemu-system-arm (Debian) and the two rustup targets.
# Fails when a firmware fails, when banded and whole-frame pictures differ, or when the
# frame is not the host's (its checksum is tests/bench_scene.rs's BENCH_CHECKSUM).
set -euo pipefail
cd "$(dirname "$0")/mcu"
# The frame checksum every build must print: the host's picture (tests/bench_scene.rs).
want=$(sed -n 's/^const BENCH_CHECKSUM: u32 = 0x\([0-9a-f_]*\);/\1/p' ../../tests/bench_scene.rs | tr -d _)
[ -n "$want" ] || { echo "no BENCH_CHECKSUM in tests/bench_scene.rs"; exit 1; }
out=$(mktemp)
status=0
for target in thumbv7em-none-eabihf thumbv6m-none-eabi; do
  echo "== $target"
  if ! timeout 300 cargo run --quiet --release --target "$target" >"$out" 2>&1; then
    cat "$out"
    echo "bench firmware failed on $target"
    status=1
    continue
  fi
  grep -Ev '^warning|^ *\||^ *=|^$|^ +-->' "$out" || true
  grep -q "same picture: true" "$out" || { echo "banded and whole-frame pictures differ on $target"; status=1; }
  grep -q "checksum $want " "$out" || { echo "the frame on $target is not the host's picture (checksum $want)"; status=1; }
done
rm -f "$out"
exit $status
