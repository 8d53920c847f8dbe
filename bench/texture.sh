#!/usr/bin/env bash
# Instructions a pixel of zraster's textured fill on the Cortex-M4F (thumbv7em) and
# Cortex-M0+ (thumbv6m) instruction sets, under QEMU's mps2-an386 board with -icount
# shift=0 (exact and repeatable): bench/mcu-texture draws bench/mcu's fill-bound cube
# (320×240 pixels of the cube's front face) untextured (the reference, bench/mcu's
# "fill-bound cube" figure), then with a 64×64 RGB565 checker from flash,
# perspective-correct, affine, and perspective-correct under Lambert light; then through
# the pixel-shader hook (Renderer::draw_with_shader): the texel shader, which must give
# the perspective-correct picture, and fog over it.
# Needs qemu-system-arm and the two rustup targets (see ../shared/QEMU-CORTEX-M.md).
# Fails when a firmware fails, when the textured segment's assembly differs from its
# portable twin on the target (src/num/kernel/texel.rs), or when a textured picture
# differs between the two targets or from the host's (tests/texture.rs pins its checksum).
# With UPDATE_README=1 it writes the README's "texture" table (bench/readme.sh).
set -euo pipefail
cd "$(dirname "$0")/mcu-texture"
# shellcheck source=SCRIPTDIR/readme.sh
source ../readme.sh
# The host's checksum of the perspective-correct picture (tests/texture.rs).
want=$(sed -n 's/^const TEXTURE_BENCH_CHECKSUM: u32 = 0x\([0-9a-f_]*\);/\1/p' ../../tests/texture.rs | tr -d _)
[ -n "$want" ] || { echo "no TEXTURE_BENCH_CHECKSUM in tests/texture.rs"; exit 1; }
out=$(mktemp)
runs=$(mktemp -d)
trap 'rm -rf "$out" "$runs"' EXIT
status=0
sums=()
for target in thumbv7em-none-eabihf thumbv6m-none-eabi; do
  echo "== $target"
  if ! timeout 600 cargo run --quiet --release --target "$target" >"$out" 2>&1; then
    cat "$out"
    echo "texture bench firmware failed on $target"
    status=1
    continue
  fi
  grep -E 'per pixel|differing' "$out" || true
  cp "$out" "$runs/$target"
  grep -q "texel kernel cases differing from the portable twin: 0$" "$out" ||
    { echo "the texel kernel differs from its portable twin on $target"; status=1; }
  grep -q "textured fill-bound cube, perspective-correct: .* (checksum $want)" "$out" ||
    { echo "the perspective-correct picture on $target is not the host's (checksum $want)"; status=1; }
  grep -q "textured fill-bound cube, shader Textured: .* (checksum $want)" "$out" ||
    { echo "the texel shader's picture on $target is not draw_textured's (checksum $want)"; status=1; }
  sums+=("$(sed -n 's/^textured.*(checksum \([0-9a-f]*\))$/\1/p' "$out" | tr '\n' ' ')")
done
if [ ${#sums[@]} = 2 ] && [ "${sums[0]}" != "${sums[1]}" ]; then
  echo "the textured pictures differ between the targets: ${sums[0]}/ ${sums[1]}"
  status=1
fi
# ---- The README's table: instructions a written pixel on each core.
per_pixel() { # per_pixel TARGET LABEL: the figure of the line starting with "LABEL:"
  sed -n "s/^$2: .* \([0-9.]*\) per pixel.*/\1/p" "$runs/$1" 2>/dev/null | head -n 1
}
row() { # row "README label" "bench label"
  echo "| $1 | $(per_pixel thumbv7em-none-eabihf "$2") | $(per_pixel thumbv6m-none-eabi "$2") |"
}
if [ "$status" = 0 ]; then
  readme_table texture "UPDATE_README=1 bash bench/texture.sh" <<TABLE
| fill-bound cube (320×240), instructions a written pixel | Cortex-M4F | M0+ instruction set |
|---|---:|---:|
$(row 'flat colour (`draw`), for comparison' "flat fill-bound cube")
$(row 'textured, perspective-correct (`draw_textured`)' "textured fill-bound cube, perspective-correct")
$(row 'textured, affine (`UvMode::Affine`)' "textured fill-bound cube, affine")
$(row 'textured, perspective-correct, Lambert' "textured fill-bound cube, perspective-correct, Lambert")
$(row 'pixel shader `Textured` (`draw_with_shader`)' "textured fill-bound cube, shader Textured")
$(row 'pixel shader `Fog(Textured)`' "textured fill-bound cube, shader Fog(Textured)")

*A 64×64 RGB565 checker from flash on the cube's front face, filling the screen; exact
counts under \`qemu-system-arm -icount shift=0\`. Written by
\`UPDATE_README=1 bash bench/texture.sh\` from its run.*
TABLE
fi
exit $status
