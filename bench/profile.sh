#!/usr/bin/env bash
# Where one measured region of the bench firmware (bench/mcu) spends its instructions,
# function by function: runs the firmware under QEMU (mps2-an386, -icount shift=0) with
# the pcprof plugin (bench/tools/pcprof.c), which counts every instruction executed
# between the firmware's bench_start/bench_stop markers.
#
#   bash bench/profile.sh [TARGET] [REGION] [FEATURES]
#
# TARGET   thumbv7em-none-eabihf (default, the M4F) or thumbv6m-none-eabi (the M0+).
# REGION   the name main.rs binds the measure(...) to: clear, transform, draw (the
#          default: the whole-frame draw), setup, banded, banded_sink, fill, ...; or the
#          region's index from 0 in the order main.rs runs them; several joined with +
#          (transform+draw) count together; "all" counts every region.
# FEATURES cargo features of bench/mcu (only-full, only-banded, only-fill), comma-separated.
#
# Prints the firmware's own lines, the top functions (TOP=40 by default) by instructions
# executed in the region with the distinct code bytes each executed and its symbol size,
# the region's total against the firmware's timer, and the region's hot code working set
# (distinct code bytes executed; all code, and zraster's functions alone). The raw
# per-instruction counts stay in bench/mcu/target/pcprof/ for llvm-objdump. With INLINED=1
# it also splits the instructions by source function and line, inlined frames included
# (from the debug info, with llvm-symbolizer).
#
# Needs qemu-system-arm, gcc and llvm-nm (Debian's llvm, or rustup's llvm-tools).
# bench/footprint.sh sources this file for its helpers (then nothing runs).
set -euo pipefail

bench=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

# The path of LLVM tool $1: on the PATH, Debian's versioned llvm-*, or rustup's llvm-tools.
llvm_tool() {
  local t
  if command -v "$1" >/dev/null 2>&1; then command -v "$1"; return 0; fi
  for t in /usr/bin/"$1"-[0-9]* /usr/lib/llvm-*/bin/"$1" "$(rustc --print sysroot 2>/dev/null)"/lib/rustlib/*/bin/"$1"; do
    if [ -x "$t" ]; then echo "$t"; return 0; fi
  done
  echo "$1 not found: apt-get install llvm (Debian), or rustup component add llvm-tools" >&2
  return 1
}

# Rust names from llvm-nm -C, finished: LLVM demangles the legacy scheme's nesting but
# leaves its escapes ($LT$, ..) and the ::h<hash> suffix.
# shellcheck disable=SC2016 # the $ are sed's
demangle() {
  sed -E -e 's/::h[0-9a-f]{16}([^0-9a-zA-Z_]|$)/\1/g' -e 's/(^|::| )_\$/\1$/g' \
    -e 's/\$LT\$/</g; s/\$GT\$/>/g; s/\$u20\$/ /g; s/\$C\$/,/g; s/\$RF\$/\&/g; s/\$BP\$/*/g' \
    -e 's/\$SP\$/@/g; s/\$LP\$/(/g; s/\$RP\$/)/g; s/\$u7b\$/{/g; s/\$u7d\$/}/g; s/\$u27\$/'"'"'/g' \
    -e 's/\$u5b\$/[/g; s/\$u5d\$/]/g; s/\$u7e\$/~/g; s/\$u3b\$/;/g; s/\.\./::/g'
}

# Builds the crate in directory $1 (release; target $2 unless empty; features $3) and
# prints the path of its executable.
build_elf() {
  local dir=$1 target=$2 features=$3 log elf
  local args=(build --release --message-format=json-render-diagnostics)
  [ -z "$target" ] || args+=(--target "$target")
  [ -z "$features" ] || args+=(--features "$features")
  log=$(mktemp)
  if ! elf=$(cd "$dir" && cargo "${args[@]}" 2>"$log" | sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1) || [ -z "$elf" ]; then
    cat "$log" >&2
    rm -f "$log"
    echo "cargo ${args[*]} failed in $dir" >&2
    return 1
  fi
  rm -f "$log"
  echo "$elf"
}

# The pcprof plugin, built on first use (and after a change) where git ignores it.
build_plugin() {
  local dir="$bench/mcu/target/pcprof" src="$bench/tools/pcprof.c"
  local so="$dir/pcprof.so"
  if [ ! -f "$so" ] || [ "$src" -nt "$so" ]; then
    mkdir -p "$dir"
    gcc -O2 -shared -fPIC -o "$so.$$" "$src"
    mv -f "$so.$$" "$so"
  fi
  echo "$so"
}

# "INDEX NAME" for each measure(...) in bench/mcu/src/main.rs, in source order (the
# order it runs them): NAME is what `let (_, NAME) = measure(` binds (the first binding
# when the second is _), "-" when the line binds nothing.
region_names() {
  awk '!/^[ \t]*\/\// && /measure\(/ && !/fn measure/ {
    n = "-"
    if (match($0, /let *\([^)]*\) *= *measure\(/)) {
      s = substr($0, RSTART, RLENGTH)
      sub(/^let *\(/, "", s); sub(/\) *= *measure\($/, "", s)
      split(s, p, / *, */)
      n = p[2]
      if (n == "_") { n = p[1]; sub(/^mut +/, "", n) }
    }
    print i++, n
  }' "$bench/mcu/src/main.rs"
}

# The figure the firmware prints (its timer, ±40) for region NAME $1, from its output $2.
firmware_figure() {
  local out=$2 a b
  case $1 in
    clear) sed -n 's/^bunny-320 full: clear \([0-9]*\) .*/\1/p' "$out" ;;
    transform) sed -n 's/^bunny-320 full: .* transform \([0-9]*\) .*/\1/p' "$out" ;;
    setup) sed -n 's/^bunny-320 full: .* cull \([0-9]*\) .*/\1/p' "$out" ;;
    draw)
      a=$(sed -n 's/^bunny-320 full: .* cull \([0-9]*\) .*/\1/p' "$out")
      b=$(sed -n 's/^bunny-320 full: .* setup+raster+output \([0-9]*\) .*/\1/p' "$out")
      if [ -n "$a" ] && [ -n "$b" ]; then echo $((a + b)); fi ;;
    banded) sed -n 's/^bunny-320 banded-16: total \([0-9]*\) .*/\1/p' "$out" ;;
    banded_sink) sed -n 's/^bunny-320 banded-16 without the copy to the frame: total \([0-9]*\)$/\1/p' "$out" ;;
    fill) sed -n 's/^fill-bound cube: \([0-9]*\) instructions.*/\1/p' "$out" ;;
  esac
}

# Sourced (by bench/footprint.sh): the functions above only.
if [ "${BASH_SOURCE[0]}" != "$0" ]; then return 0; fi

target=${1:-thumbv7em-none-eabihf}
region=${2:-draw}
features=${3:-}
top=${TOP:-40}

# The region's index and name; several joined with + count together.
names=$(region_names)
if [ "$region" = all ]; then
  index=all name=all
else
  index='' name=''
  for part in ${region//+/ }; do
    case $part in
      *[!0-9]*) i=$(echo "$names" | awk -v n="$part" '$2 == n { print $1; exit }') n=$part ;;
      *) i=$part n=$(echo "$names" | awk -v i="$part" '$1 == i { print $2 }') ;;
    esac
    if [ -z "$i" ] || [ -z "$n" ]; then
      echo "no region $part in bench/mcu/src/main.rs; its regions:" >&2
      printf '  %s\n' "${names//$'\n'/$'\n  '}" >&2
      exit 1
    fi
    index=$index${index:++}$i name=$name${name:++}$n
  done
fi

nm=$(llvm_tool llvm-nm)
elf=$(build_elf "$bench/mcu" "$target" "$features")
so=$(build_plugin)

# The marker functions' addresses, from the symbol table (QEMU's own lookup would do
# too; this way a renamed marker fails here, loudly).
syms=$(mktemp)
fw=$(mktemp)
tab=$(mktemp)
trap 'rm -f "$syms" "$fw" "$tab"' EXIT
"$nm" -S -n --defined-only -C "$elf" | demangle >"$syms"
start=$(awk '$NF == "bench_start" { print $1; exit }' "$syms")
stop=$(awk '$NF == "bench_stop" { print $1; exit }' "$syms")
if [ -z "$start" ] || [ -z "$stop" ]; then
  echo "no bench_start/bench_stop symbols in $elf" >&2
  exit 1
fi

out="$bench/mcu/target/pcprof/profile-$target-$name${features:+-${features//,/-}}.txt"
if ! timeout 300 qemu-system-arm -cpu cortex-m4 -machine mps2-an386 -nographic \
  -semihosting-config enable=on,target=native -icount shift=0 \
  -plugin "$so,region=$index,start=$start,stop=$stop,out=$out" -kernel "$elf" >"$fw" 2>&1; then
  cat "$fw"
  echo "the firmware failed under QEMU ($elf)" >&2
  exit 1
fi
cat "$fw"
if [ "$index" != all ]; then
  for i in ${index//+/ }; do
    if ! grep -q "^# region $i insns" "$out"; then
      echo "the firmware ran no region $i ($(grep -c '^# region [0-9]* insns' "$out") regions)" >&2
      exit 1
    fi
  done
fi
total=$(sed -n 's/^# selected .* insns \([0-9]*\)$/\1/p' "$out")

echo
echo "== region $index ($name) on $target${features:+ with $features}: $total instructions"

# Each executed instruction goes to the function symbol whose [address, address + size)
# holds it (Thumb: the symbol's bit 0 cleared); one not in any goes to the last symbol
# before it, marked "(no size)". Names that several symbols share get their address.
awk -v top="$top" -v total="$total" '
  function hex(s,   i, v) {
    s = tolower(s); sub(/^0x/, "", s); v = 0
    for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
    return v
  }
  FNR == NR {
    if ($2 ~ /^[0-9a-fA-F]+$/ && length($3) == 1) { size = hex($2); type = $3; nf = 3 }
    else if (length($2) == 1) { size = 0; type = $2; nf = 2 }
    else next
    if (type !~ /^[tTW]$/) next
    name = $0; for (k = 1; k <= nf; k++) sub(/^[^ ]+ +/, "", name)
    a = hex($1); a -= a % 2
    n++; addr[n] = a; len[n] = size; label[n] = name; uses[name]++
    next
  }
  /^#/ { next }
  {
    a = hex($1)
    lo = 1; hi = n; at = 0
    while (lo <= hi) { mid = int((lo + hi) / 2); if (addr[mid] <= a) { at = mid; lo = mid + 1 } else hi = mid - 1 }
    f = 0
    for (j = at; j >= 1 && j > at - 16; j--) if (len[j] > 0 && a < addr[j] + len[j]) { f = j; break }
    if (!f) { f = at ? at : 0; nosize[f] = 1 }
    insns[f] += $3; bytes[f] += $2; hot[f] = 1
    hot_bytes += $2
  }
  END {
    for (k in hot) {
      f = k + 0
      nm = f ? label[f] : "?"
      if (f && uses[nm] > 1) nm = nm sprintf(" [%x]", addr[f])
      if (nosize[f]) nm = nm " (no size)"
      printf "%d\t%d\t%d\t%s\n", insns[f], bytes[f], f ? len[f] : 0, nm
      funcs++
      if (label[f] ~ /zraster::/) { z_bytes += bytes[f]; z_funcs++ }
    }
    printf "#hot\t%d\t%d\t%d\t%d\n", hot_bytes, funcs, z_bytes, z_funcs
  }' "$syms" "$out" >"$tab"

printf '%12s %6s %10s %11s  %s\n' instructions % "code bytes" "symbol size" function
grep -v '^#' "$tab" | sort -t "$(printf '\t')" -k1,1nr -k4 |
  awk -F '\t' -v total="$total" -v top="$top" 'NR <= top { printf "%12d %5.1f%% %10d %11d  %s\n", $1, total ? $1 * 100 / total : 0, $2, $3, $4 }'
funcs=$(grep -vc '^#' "$tab" || true)
[ "$funcs" -le "$top" ] || echo "($((funcs - top)) more functions; TOP=N shows N)"
echo

# The region's total against the firmware's own figures (its timer counts in steps of 40,
# each region's figure is within ±40 of the plugin's count).
figure=0 parts=0
for n in ${name//+/ }; do
  f=$(firmware_figure "$n" "$fw")
  if [ -z "$f" ]; then figure=; break; fi
  figure=$((figure + f)) parts=$((parts + 1))
done
if [ -n "$figure" ] && [ "$name" != all ]; then
  diff=$((total - figure))
  within=yes
  [ "${diff#-}" -le $((40 * parts)) ] || within=no
  echo "region total: $total instructions; the firmware's timer: $figure; difference $diff (within ±$((40 * parts)): $within)"
else
  echo "region total: $total instructions (the firmware prints no figure for this region)"
fi
# The hot code working set: the code the region runs, each instruction's bytes once.
read -r _ hot_bytes hot_funcs z_bytes z_funcs < <(grep '^#hot' "$tab" | tr '\t' ' ')
echo "hot code working set: $hot_bytes bytes in $hot_funcs functions"
echo "hot code working set, zraster:: functions: $z_bytes bytes in $z_funcs functions"
echo "per-instruction counts (address size count): $out"

# With INLINED=1: the same instructions by the source function and line the debug info
# gives them (the innermost inlined frame outside Rust's standard library, else the
# innermost), since LTO
# inlines most of zraster into a few symbols.
if [ "${INLINED:-}" = 1 ]; then
  symbolizer=$(llvm_tool llvm-symbolizer)
  root=$(cd "$bench/.." && pwd)
  grep -v '^#' "$out" | cut -d ' ' -f 1 | "$symbolizer" --obj="$elf" -C | demangle >"$syms"
  grep -v '^#' "$out" | awk -v root="$root/" -v top="$top" -v total="$total" '
    FNR == NR { n++; count[n] = $3; size[n] = $2; next }
    {
      i++; f = $1; l = $2; sub(/:[0-9]+$/, "", l); sub(/^\/rustc\/[0-9a-f]+\//, "", l)
      if (f ~ /^\?\?/) f = "?"
      for (k = 1; k < NF; k += 2) {
        if ($(k + 1) ~ /^\/rustc\// || $(k + 1) ~ /^\?\?/) continue
        f = $k; l = $(k + 1); sub(/:[0-9]+$/, "", l); break
      }
      if (index(l, root) == 1) l = substr(l, length(root) + 1)
      fi[f] += count[i]; fb[f] += size[i]; li[l "\t" f] += count[i]
    }
    END {
      for (f in fi) printf "F\t%d\t%d\t%s\n", fi[f], fb[f], f
      for (l in li) printf "L\t%d\t%s\n", li[l], l
    }' - RS= FS='\n' "$syms" >"$tab"
  echo
  echo "== by source function (inlined frames, from the debug info)"
  printf '%12s %6s %10s  %s\n' instructions % "code bytes" function
  grep '^F' "$tab" | sort -t "$(printf '\t')" -k2,2nr -k4 |
    awk -F '\t' -v total="$total" -v top="$top" 'NR <= top { printf "%12d %5.1f%% %10d  %s\n", $2, total ? $2 * 100 / total : 0, $3, $4 }'
  echo
  echo "== by source line"
  printf '%12s %6s  %s\n' instructions % line
  grep '^L' "$tab" | sort -t "$(printf '\t')" -k2,2nr -k3 |
    awk -F '\t' -v total="$total" -v top="$top" 'NR <= top { printf "%12d %5.1f%%  %s (%s)\n", $2, total ? $2 * 100 / total : 0, $3, $4 }'
fi
