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
set -euo pipefail
cd "$(dirname "$0")/mcu-texture"
# The host's checksum of the perspective-correct picture (tests/texture.rs).
want=$(sed -n 's/^const TEXTURE_BENCH_CHECKSUM: u32 = 0x\([0-9a-f_]*\);/\1/p' ../../tests/texture.rs | tr -d _)
[ -n "$want" ] || { echo "no TEXTURE_BENCH_CHECKSUM in tests/texture.rs"; exit 1; }
out=$(mktemp)
trap 'rm -f "$out"' EXIT
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
exit $status
