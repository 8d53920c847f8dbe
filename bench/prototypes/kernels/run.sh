#!/bin/sh
# Build the firmware for both instruction sets and run it under QEMU with the exact-count
# plugin; writes run-m4.log and run-m0.log (timer figures and the plugin's region lines).
set -e
cd "$(dirname "$0")/fw"
tools="$(cd .. && pwd)/tools/qemu-m4"
for t in thumbv7em-none-eabihf:m4 thumbv6m-none-eabi:m0; do
  target=${t%%:*}; tag=${t##*:}
  cargo build --release --target "$target" 2>&1 | grep -E "^(warning|error)" -A6 || true
  REGIONCOUNT=1 "$tools/run.sh" "target/$target/release/zkern-fw" > "../run-$tag.log" 2>&1 || { tail -5 "../run-$tag.log"; exit 1; }
done
