#!/usr/bin/env bash
# zraster's footprint: the code it puts in the RP2040 firmware (examples/firmware/
# rp2040-st7789, thumbv6m-none-eabi), that firmware's static RAM, and the hot code
# working set (distinct code bytes a region executes) of the bench firmware on the M0+
# instruction set (bench/mcu under QEMU, through bench/profile.sh and its plugin).
# Fails when one of the gated figures grows more than 5 % over bench/footprint-baseline.txt:
#   rp2040 zraster-code  text symbols named zraster::… (its functions, and generic code
#                        instantiated for its types: <zraster::… as …>, …<zraster::…>)
#                        and its global_asm! functions (zraster_…) placed in flash
#   rp2040 static-ram    .data + .bss (+ .uninit)
#   m0plus hot-banded    the bench's banded bunny drawn into a display that drops the
#                        bands (region banded_sink of bench/mcu/src/main.rs)
# UPDATE_BASELINE=1 bash bench/footprint.sh rewrites bench/footprint-baseline.txt.
# UPDATE_README=1 bash bench/footprint.sh rewrites the README's table `footprint` (the
# figures above, the largest functions and statics, the three hot working sets); without
# it, a `readme:` line says whether the README holds this run's figures (bench/readme.sh).
# Needs what bench/profile.sh needs (qemu-system-arm, gcc, llvm-nm and llvm-size from
# Debian's llvm or rustup's llvm-tools) and the rustup target thumbv6m-none-eabi.
set -euo pipefail
bench=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=SCRIPTDIR/profile.sh
source "$bench/profile.sh"
# shellcheck source=SCRIPTDIR/readme.sh
source "$bench/readme.sh"
baseline="$bench/footprint-baseline.txt"
limit=5
nm=$(llvm_tool llvm-nm)
size=$(llvm_tool llvm-size)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
status=0

# ---- The RP2040 firmware.
echo "== examples/firmware/rp2040-st7789 (thumbv6m-none-eabi)"
elf=$(build_elf "$bench/../examples/firmware/rp2040-st7789" "" "")
"$nm" -S --size-sort --defined-only -C "$elf" | demangle >"$tmp/syms"

# zraster's code: text symbols whose names mention zraster:: (aliases counted once), and
# its global_asm! functions (zraster_…) where they sit in flash (in RAM they count there).
awk '$3 ~ /^[tTW]$/ && $2 !~ /^0+$/ && !seen[$1]++ { name = $0; sub(/^[^ ]+ +[^ ]+ +[^ ]+ +/, "", name); if (name ~ /zraster::/ || (name ~ /^zraster_[a-z0-9_]+$/ && $1 !~ /^2/)) print $2, name }' \
  "$tmp/syms" | while read -r hexsize name; do echo "$((16#$hexsize)) $name"; done | sort -k1,1nr -k2 >"$tmp/zraster"
zcode=$(awk '{ s += $1 } END { print s + 0 }' "$tmp/zraster")
echo "rp2040 zraster code: $zcode bytes in $(wc -l <"$tmp/zraster") functions"
head -n 15 "$tmp/zraster" | awk '{ size = $1; sub(/^[^ ]+ /, ""); printf "  %7d  %s\n", size, $0 }'

# Sections: code and flash data, static RAM.
sections=$("$size" -A "$elf")
section() { echo "$sections" | awk -v s="$1" '$1 == s { print $2; found = 1 } END { if (!found) print 0 }'; }
text=$(section .text)
rodata=$(section .rodata)
data=$(section .data)
bss=$(section .bss)
uninit=$(section .uninit)
ram=$((data + bss + uninit))
echo "rp2040 .text: $text bytes (all code; .rodata $rodata bytes)"
echo "rp2040 static RAM: $ram bytes (.data $data + .bss $bss + .uninit $uninit)"
awk '$3 ~ /^[bBdD]$/ && $2 !~ /^0+$/ && !seen[$1]++ { name = $0; sub(/^[^ ]+ +[^ ]+ +[^ ]+ +/, "", name); print $2, ($3 ~ /[bB]/ ? ".bss " : ".data"), name }' \
  "$tmp/syms" | while read -r hexsize sec name; do echo "$((16#$hexsize)) $sec $name"; done | sort -k1,1nr >"$tmp/statics"
awk 'NR <= 8 { size = $1; sec = $2; sub(/^[^ ]+ [^ ]+ /, ""); printf "  %7d  %-5s  %s\n", size, sec, $0 }' "$tmp/statics"

# ---- The bench firmware's hot code working sets on the M0+.
echo
echo "== bench/mcu on the M0+ (thumbv6m-none-eabi, QEMU): hot code working sets"
# hot_set REGION LABEL: prints the figures of bench/profile.sh for REGION; sets $hot.
hot_set() {
  local out="$tmp/profile-$1" all z check insns
  if ! bash "$bench/profile.sh" thumbv6m-none-eabi "$1" >"$out" 2>&1; then
    cat "$out"
    echo "bench/profile.sh thumbv6m-none-eabi $1 failed"
    exit 1
  fi
  all=$(sed -n 's/^hot code working set: \([0-9]*\) bytes.*/\1/p' "$out")
  z=$(sed -n 's/^hot code working set, zraster:: functions: \([0-9]*\) bytes.*/\1/p' "$out")
  check=$(grep '^region total:' "$out" || true)
  # The region main.rs names must be the one the firmware measured: the same count (±40).
  if [ -z "$all" ] || ! echo "$check" | grep -q 'within ±[0-9]*: yes'; then
    cat "$out"
    echo "the $1 region's count is not the firmware's figure: has bench/mcu/src/main.rs changed?"
    exit 1
  fi
  insns=${check#region total: }
  echo "hot working set (M0+, $2): $all bytes (zraster:: functions $z bytes; ${insns%% *} instructions)"
  hot=$all
  # The README's row: bytes, zraster:: bytes, instructions.
  hot_row="| $(readme_num "$all") | $(readme_num "$z") | $(readme_num "${insns%% *}") |"
}
hot_set banded_sink "banded bunny"
banded=$hot
hot_banded=$hot_row
hot_set draw "whole-frame draw"
hot_draw=$hot_row
hot_set transform+draw "whole frame with its transform, like the banded one"
hot_both=$hot_row

# ---- The README's table (bench/readme.sh).
echo
# The statics of 64 bytes or more, by name (the firmware's own without its crate path),
# then whatever else the static RAM holds, in one row.
statics=$(awk -v ram="$ram" '
  $1 >= 64 { size = $1; sec = $2; sub(/^[^ ]+ [^ ]+ /, ""); sub(/^zraster_rp2040_st7789::/, "");
             printf "| `%s` %s | %d |\n", sec, "`" $0 "`", size; shown += size }
  END { if (ram > shown) printf "| the rest of `.data`, `.bss` and `.uninit` (smaller statics, code run from RAM, padding) | %d |\n", ram - shown }' "$tmp/statics" |
  while IFS='|' read -r _ label size _; do echo "|${label}| $(readme_num "${size// /}") |"; done)
largest=$(head -n 8 "$tmp/zraster" | while read -r size name; do echo "| \`$name\` | $(readme_num "$size") |"; done)
readme_table footprint "UPDATE_README=1 bash bench/footprint.sh" <<EOF
| Raspberry Pi Pico firmware (\`examples/firmware/rp2040-st7789\`, thumbv6m-none-eabi) | bytes |
|---|---:|
| zraster's code: $(wc -l <"$tmp/zraster") functions named \`zraster::…\` | $(readme_num "$zcode") |
| all code (\`.text\`) | $(readme_num "$text") |
| flash data (\`.rodata\`) | $(readme_num "$rodata") |
| static RAM (\`.data\` + \`.bss\` + \`.uninit\`) | $(readme_num "$ram") |
$statics

| zraster's largest functions in that firmware | bytes |
|---|---:|
$largest

| hot code working set on the M0+ (\`bench/mcu\` under QEMU) | bytes | in \`zraster::\` functions | instructions |
|---|---:|---:|---:|
| the banded bunny (region \`banded_sink\`) $hot_banded
| the whole-frame draw (\`draw\`) $hot_draw
| the whole frame with its transform (\`transform+draw\`), like for like with the banded one $hot_both

*Written by \`UPDATE_README=1 bash bench/footprint.sh\` from its run: symbol sizes by
\`llvm-nm\`, sections by \`llvm-size\`, working sets by \`bench/profile.sh\`.*
EOF

# ---- Against the baseline.
echo
base() { if [ -f "$baseline" ]; then awk -v a="$1" -v b="$2" '$1 == a && $2 == b { print $3 }' "$baseline"; fi; }
fresh="rp2040 zraster-code $zcode
rp2040 static-ram $ram
m0plus hot-banded $banded"
if [ "${UPDATE_BASELINE:-}" = 1 ]; then
  {
    echo "# The figures bench/footprint.sh compares against, in bytes: zraster's code in the RP2040"
    echo "# firmware (text symbols named zraster::), that firmware's static RAM (.data + .bss +"
    echo "# .uninit), and the distinct code bytes the bench's banded bunny (region banded_sink of"
    echo "# bench/mcu) executes on the M0+. bench/footprint.sh fails when one grows more than $limit %."
    echo "# A change that moves them updates this file in the same commit, with"
    echo "#   UPDATE_BASELINE=1 bash bench/footprint.sh"
    echo "$fresh"
  } >"$baseline"
  echo "bench/footprint-baseline.txt rewritten"
  exit 0
fi
while read -r a b new; do
  old=$(base "$a" "$b")
  if [ -z "$old" ]; then
    echo "footprint: no $a $b in bench/footprint-baseline.txt (UPDATE_BASELINE=1 bash bench/footprint.sh writes it)"
    status=1
    continue
  fi
  echo "footprint: $a $b $old -> $new ($(awk -v o="$old" -v n="$new" 'BEGIN { printf "%+.2f %%", (n - o) * 100 / o }'))"
  if [ $((new * 100)) -gt $((old * (100 + limit))) ]; then
    echo "footprint: $a $b grew more than $limit % over bench/footprint-baseline.txt"
    status=1
  elif [ $((new * 100)) -lt $((old * (100 - limit))) ]; then
    echo "footprint: $a $b is more than $limit % below the baseline: update it so the gate keeps the gain"
  fi
done <<<"$fresh"
if [ "$status" != 0 ]; then
  echo "(if that is the price of a change, update the baseline in the same commit: UPDATE_BASELINE=1 bash bench/footprint.sh)"
fi
exit $status
