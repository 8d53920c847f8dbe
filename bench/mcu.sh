#!/usr/bin/env bash
# Instruction counts of zraster on the Cortex-M4F (thumbv7em) and Cortex-M0+ (thumbv6m)
# instruction sets, under QEMU's mps2-an386 board with -icount shift=0 (exact, repeatable).
# Needs qemu-system-arm (Debian) and the two rustup targets; installs neither itself
# unless MCU_INSTALL=1 (CI sets it).
set -euo pipefail
cd "$(dirname "$0")/mcu"
if [ "${MCU_INSTALL:-0}" = 1 ]; then
  command -v qemu-system-arm >/dev/null || { apt-get update -qq && apt-get install -y -qq --no-install-recommends qemu-system-arm >/dev/null; }
  rustup target add thumbv7em-none-eabihf thumbv6m-none-eabi >/dev/null
fi
status=0
for target in thumbv7em-none-eabihf thumbv6m-none-eabi; do
  echo "== $target"
  if ! timeout 300 cargo run --quiet --release --target "$target" 2>&1 | grep -v '^warning\|^ *|\|^ *=\|^$'; then
    status=1
  fi
  [ "${PIPESTATUS[0]}" = 0 ] || status=1
done
exit $status
