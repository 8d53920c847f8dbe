#!/bin/sh
# Generate span.rs with the given unrolls, host-test it, run both firmwares, save tables.
# Usage: ./variant.sh U4 U0   (writes table-m4-u$U4.txt, table-m0-u$U0.txt, run logs)
set -e
cd "$(dirname "$0")"
python3 gen/gen.py "$1" "$2"
(cd kern && cargo test --release 2>&1 | grep -E "test result|panicked|FAILED" | head -3)
./run.sh
cp run-m4.log "run-m4-u$1.log"; cp run-m0.log "run-m0-u$2.log"
python3 table.py run-m4.log > "table-m4-u$1.txt"
python3 table.py run-m0.log > "table-m0-u$2.txt"
