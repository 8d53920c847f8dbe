#!/usr/bin/env bash
# The performance figures of the README, reproducibly:
#  - x86-64: instructions per bunny-320 frame of the render example, counted by
#    callgrind as (Ir(2N) - Ir(N)) / N, so start-up and PNG writing cancel out;
#  - Cortex-M4F and M0+ instruction sets: the QEMU bench (bench/mcu.sh).
# Needs valgrind (Debian) for the first part; bench/mcu.sh needs qemu-system-arm (Debian)
# and the rustup targets thumbv7em-none-eabihf and thumbv6m-none-eabi, and fails when a
# whole frame costs more than 2 % over bench/baseline.txt.
# UPDATE_README=1 bash bench/perf.sh rewrites the README's tables: bench/mcu.sh writes them,
# with the x86-64 figures measured here (README_X86_FULL, README_X86_BANDED).
set -euo pipefail
cd "$(dirname "$0")/.."
N=${N:-10}
cargo build --quiet --release --example render
args=(examples/models/bunny.obj --yaw 30 --distance 1.6 --color 1,0.8,0.6 --shade lambert --out /tmp/zraster-perf.png)
ir() {
  valgrind --tool=callgrind --callgrind-out-file=/dev/null target/release/examples/render "${args[@]}" --frames "$1" 2>&1 \
    | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
a=$(ir "$N"); b=$(ir $((2 * N)))
echo "x86-64 bunny-320: $(( (b - a) / N )) instructions per frame (callgrind, frames $N and $((2 * N)))"
args+=(--band 16)
c=$(ir "$N"); d=$(ir $((2 * N)))
echo "x86-64 bunny-320 banded 16: $(( (d - c) / N )) instructions per frame"
README_X86_FULL=$(( (b - a) / N )) README_X86_BANDED=$(( (d - c) / N )) bash bench/mcu.sh
