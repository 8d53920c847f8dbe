#!/usr/bin/env bash
# Instruction counts of zraster on the Cortex-M4F (thumbv7em) and Cortex-M0+ (thumbv6m)
# instruction sets, under QEMU's mps2-an386 board with -icount shift=0 (exact and
# repeatable). Needs qemu-system-arm (Debian) and the two rustup targets.
# Fails when a firmware fails, when an assembly loop (the fill, the span or the rows) differs from
# its portable twin, when banded and whole-frame pictures differ, when the frame is not
# the host's (its checksum is tests/bench_scene.rs's BENCH_CHECKSUM), or when a
# bunny-320 whole frame costs more than 2 % over bench/baseline.txt.
# UPDATE_BASELINE=1 bash bench/mcu.sh rewrites bench/baseline.txt with this run's figures
# (see bench/README.md: a change that moves them updates it in the same commit).
# UPDATE_README=1 bash bench/mcu.sh rewrites the README's tables `comparison` (its QEMU
# columns; the x86-64 cells are kept, or taken from README_X86_FULL and README_X86_BANDED,
# which bench/perf.sh sets) and `mcu` (per stage) from this run's figures; without it,
# a `readme:` line says whether the README holds them (bench/readme.sh).
set -euo pipefail
cd "$(dirname "$0")/mcu"
# shellcheck source=SCRIPTDIR/readme.sh
source ../readme.sh
baseline=../baseline.txt
# The gate: a whole frame may cost at most this many per cent over the baseline.
limit=2
# The frame checksum every build must print: the host's picture (tests/bench_scene.rs).
want=$(sed -n 's/^const BENCH_CHECKSUM: u32 = 0x\([0-9a-f_]*\);/\1/p' ../../tests/bench_scene.rs | tr -d _)
[ -n "$want" ] || { echo "no BENCH_CHECKSUM in tests/bench_scene.rs"; exit 1; }
out=$(mktemp)
fresh=$(mktemp)
trap 'rm -f "$out" "$fresh"' EXIT
status=0
slower=()
# This run's figures for the README, by "TARGET KEY".
declare -A fig

# The figure KEY of TARGET in the baseline file (empty when it has none).
base() { if [ -f "$baseline" ]; then awk -v t="$1" -v k="$2" '$1 == t && $2 == k { print $3 }' "$baseline"; fi; }
# "+0.07 %": how far NEW is from OLD.
pct() { awk -v o="$1" -v n="$2" 'BEGIN { printf "%+.2f %%", (n - o) * 100 / o }'; }

# The README's tables from this run's figures (fig), through bench/readme.sh.
m4=thumbv7em-none-eabihf
m0=thumbv6m-none-eabi
# "| 1,848,000 | 4,775,520 |": figure KEY on both targets; EMPH (** for bold) around each.
both() { printf '| %s%s%s | %s%s%s |' "$2" "$(readme_num "${fig[$m4 $1]}")" "$2" "$2" "$(readme_num "${fig[$m0 $1]}")" "$2"; }
# "frame 153600 + depth 153600 + vertex cache 14712" of TARGET -> "153,600 + 153,600 + 14,712".
parts() {
  local n out=""
  while read -r n; do out+="${out:+ + }$(readme_num "$n")"; done < <(grep -o '[0-9][0-9]*' <<<"${fig[$1 ram-parts]}")
  echo "$out"
}
readme_tables() {
  local x86_full x86_banded
  x86_full=${README_X86_FULL:-$(readme_cell comparison "zraster, whole frame" 2)}
  x86_banded=${README_X86_BANDED:-$(readme_cell comparison "zraster, 16-row bands (each band copied into a frame buffer)" 2)}
  # The first five rows are the comparison's reference figures, measured once.
  readme_table comparison "UPDATE_README=1 bash bench/perf.sh, or bench/mcu.sh for the QEMU columns" <<EOF
| renderer | x86-64 (callgrind) | Cortex-M4F (QEMU) | M0+ instruction set (QEMU) |
|---|---:|---:|---:|
| tgx \`drawMesh\` (float) | 1,942,975 | – | – |
| tgx \`drawTriangles\` | 2,579,429 | – | – |
| small3dlib (integer, 32-bit Z) | 3,639,752 | 3,648,102 | – |
| a plain float edge-function reference | 1,984,583 | 2,283,956 | – |
| floor: clearing both buffers + writing the covered pixels | 31,228 | – | – |
| **zraster, whole frame** | **$(readme_num "${x86_full:-–}")** $(both full '**')
| **zraster, 16-row bands** (each band copied into a frame buffer) | **$(readme_num "${x86_banded:-–}")** $(both copied '**')
| **zraster, 16-row bands** (bands handed to a display that drops them) | – $(both banded '**')

*zraster's rows: written by \`UPDATE_README=1 bash bench/perf.sh\` (x86-64, then the QEMU
columns through \`bench/mcu.sh\`); \`UPDATE_README=1 bash bench/mcu.sh\` alone rewrites the
QEMU columns and keeps the x86-64 figures.*
EOF
  readme_table mcu "UPDATE_README=1 bash bench/mcu.sh" <<EOF
| bunny-320 | Cortex-M4F | M0+ instruction set |
|---|---:|---:|
| clear colour + depth (store-multiple, \`src/num/kernel/\`) $(both clear '')
| vertex transform into the 8-byte cache $(both transform '')
| culling (and each front face's colour and its rejection by a band no triangle reaches) $(both cull '')
| setup, rasterization and pixels ($(readme_num "${fig[$m4 drawn]}") triangles, $(readme_num "${fig[$m4 written]}") pixels) $(both setup '')
| **whole frame** $(both full '**')
| 16-row bands, each copied into a frame buffer $(both copied '')
| 16-row bands handed to a display that drops them $(both banded '')
| fill-bound frame (the cube filling the 320×240 screen): instructions a written pixel $(both fill '')
| static RAM of the bench firmware, bytes: colour + depth + vertex cache | $(parts $m4) = $(readme_num "${fig[$m4 ram]}") | $(parts $m0) = $(readme_num "${fig[$m0 ram]}") |
| stack high-water mark of the bench firmware, bytes $(both stack '')

*Instructions, except the last two rows: exact counts under \`qemu-system-arm -icount shift=0\`.
Written by \`UPDATE_README=1 bash bench/mcu.sh\` from its run.*
EOF
}

for target in thumbv7em-none-eabihf thumbv6m-none-eabi; do
  echo "== $target"
  if ! timeout 300 cargo run --quiet --release --target "$target" >"$out" 2>&1; then
    cat "$out"
    echo "bench firmware failed on $target"
    status=1
    continue
  fi
  grep -Ev '^warning|^ *\||^ *=|^$|^ +-->' "$out" || true
  grep -q "fill kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly fill loop differs from its portable twin on $target"; status=1; }
  grep -q "span kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly span loop differs from its portable twin on $target"; status=1; }
  grep -q "rows kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly rows loop differs from its portable twin on $target"; status=1; }
  grep -q "rows walk kernel cases differing from the portable twin: 0$" "$out" || { echo "the ARMv6-M assembly rows loop differs from its portable twin on $target"; status=1; }
  grep -q "cull kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly cull scan differs from its portable twin on $target"; status=1; }
  grep -q "bin kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly binning scan differs from its portable twin on $target"; status=1; }
  grep -q "faces kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly face loop differs from its portable twin on $target"; status=1; }
  grep -q "band faces kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly band loop differs from its portable twin on $target"; status=1; }
  grep -q "band carry kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly band loop keeping set-ups differs from its portable twin on $target"; status=1; }
  grep -q "band faces v6m kernel cases differing from the portable twin: 0$" "$out" || { echo "the ARMv6-M assembly band loop differs from its portable twins on $target"; status=1; }
  grep -q "^faces v6m kernel cases differing from the portable twin: 0$" "$out" || { echo "the ARMv6-M assembly face loop differs from its portable twins on $target"; status=1; }
  grep -q "light kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly face light differs from its portable twin on $target"; status=1; }
  grep -q "place kernel cases differing from the portable twin: 0$" "$out" || { echo "the assembly vertex loop differs from its portable twin on $target"; status=1; }
  grep -q "place v6m kernel cases differing from the portable twin: 0$" "$out" || { echo "the ARMv6-M assembly vertex loop differs from its portable twin on $target"; status=1; }
  grep -q "same picture: true" "$out" || { echo "banded and whole-frame pictures differ on $target"; status=1; }
  grep -q "checksum $want " "$out" || { echo "the frame on $target is not the host's picture (checksum $want)"; status=1; }

  # The figures the baseline holds, from the lines above.
  full=$(sed -n 's/^bunny-320 full: .* total \([0-9][0-9]*\)$/\1/p' "$out")
  banded=$(sed -n 's/^bunny-320 banded-16 without the copy to the frame: total \([0-9][0-9]*\)$/\1/p' "$out")
  fill=$(sed -n 's/^fill-bound cube: .* \([0-9][0-9]*\.[0-9][0-9]\) per pixel$/\1/p' "$out")
  ram=$(sed -n 's/^static RAM \([0-9][0-9]*\) bytes.*/\1/p' "$out")
  if [ -z "$full" ] || [ -z "$banded" ] || [ -z "$fill" ] || [ -z "$ram" ]; then
    echo "could not read the figures of $target for the baseline"
    status=1
    continue
  fi
  printf '%s full %s\n%s banded %s\n%s fill-per-pixel %s\n%s static-ram %s\n' \
    "$target" "$full" "$target" "$banded" "$target" "$fill" "$target" "$ram" >>"$fresh"

  # The README's figures, from the same lines.
  read -r fig["$target clear"] fig["$target transform"] fig["$target cull"] fig["$target setup"] < <(
    sed -n 's/^bunny-320 full: clear \([0-9]*\) transform \([0-9]*\) cull \([0-9]*\) setup+raster+output \([0-9]*\) total .*/\1 \2 \3 \4/p' "$out")
  read -r fig["$target drawn"] fig["$target written"] < <(
    sed -n 's/^bunny-320 stats: drawn \([0-9]*\) written \([0-9]*\) .*/\1 \2/p' "$out")
  fig["$target full"]=$full
  fig["$target banded"]=$banded
  fig["$target fill"]=$fill
  fig["$target copied"]=$(sed -n 's/^bunny-320 banded-16: total \([0-9]*\) .*/\1/p' "$out")
  fig["$target ram-parts"]=$(sed -n 's/^static RAM [0-9]* bytes (\(.*\)); .*/\1/p' "$out")
  fig["$target ram"]=$ram
  fig["$target stack"]=$(sed -n 's/.*; stack high-water \([0-9]*\) bytes$/\1/p' "$out")

  # The comparison with the baseline.
  old=$(base "$target" full)
  if [ -z "$old" ]; then
    echo "baseline: none for $target in bench/baseline.txt (UPDATE_BASELINE=1 bash bench/mcu.sh writes it)"
    [ "${UPDATE_BASELINE:-}" = 1 ] || status=1
    continue
  fi
  echo "baseline: whole frame $old -> $full ($(pct "$old" "$full"); the gate fails above +$limit %)"
  if [ $((full * 100)) -gt $((old * (100 + limit))) ]; then
    slower+=("$target")
  elif [ $((full * 100)) -lt $((old * (100 - limit))) ]; then
    echo "baseline: the whole frame on $target is more than $limit % below the baseline: update it so the gate keeps the gain"
  fi
  old=$(base "$target" banded)
  [ -z "$old" ] || echo "baseline: banded, no copy $old -> $banded ($(pct "$old" "$banded"))"
  old=$(base "$target" fill-per-pixel)
  [ -z "$old" ] || echo "baseline: fill $old -> $fill instructions a pixel"
  old=$(base "$target" static-ram)
  [ -z "$old" ] || echo "baseline: RAM $old -> $ram bytes"
done

# ---- The README's tables (bench/readme.sh), from a run that passed its checks.
if [ "$status" = 0 ]; then
  readme_tables
fi

if [ "${UPDATE_BASELINE:-}" = 1 ]; then
  if [ "$status" != 0 ]; then
    echo "bench/baseline.txt not rewritten: the run failed"
    exit 1
  fi
  {
    echo "# The figures bench/mcu.sh compares against: exact instruction counts of bench/mcu under"
    echo "# QEMU (bunny-320 whole frame, 16-row banded frame without the copy to the frame, the"
    echo "# fill-bound cube's instructions a pixel) and the firmware's static RAM in bytes."
    echo "# bench/mcu.sh fails when a whole frame costs more than $limit % over its figure here."
    echo "# A change that moves the figures updates this file in the same commit, with"
    echo "#   UPDATE_BASELINE=1 bash bench/mcu.sh"
    cat "$fresh"
  } >"$baseline"
  echo "bench/baseline.txt rewritten"
  exit 0
fi
for target in "${slower[@]}"; do
  echo "the bunny-320 whole frame on $target costs more than $limit % over bench/baseline.txt"
  status=1
done
if [ ${#slower[@]} -gt 0 ]; then
  echo "(if that is the price of a change, update the baseline in the same commit: UPDATE_BASELINE=1 bash bench/mcu.sh)"
fi
exit $status
