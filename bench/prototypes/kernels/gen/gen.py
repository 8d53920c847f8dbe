"""Expands gen/span_template.rs into kern/src/span.rs (the asm pixel blocks are repetitive).
Usage: python3 gen/gen.py [M4 unroll: 4 or 8] [ARMv6-M unroll: 8 or 16]"""
import os, sys
here = os.path.dirname(os.path.abspath(__file__))
U4 = int(sys.argv[1]) if len(sys.argv) > 1 else 8
U0 = int(sys.argv[2]) if len(sys.argv) > 2 else 8
assert U4 in (4, 8) and U0 in (8, 16)
t = open(os.path.join(here, 'span_template.rs')).read()
I = '            '
def L(lines): return [I + '"' + l + '",' for l in lines]

# ---- ARMv6-M
def v6m_blocks(count, color=True):
    out = []
    for k in range(U0):
        out += [f"ldrh r4, [r0, #{2*k}]", "lsrs r5, r2, #16", "cmp r5, r4",
                f"bhs {(30 if count else 60)+k}f", f"strh r5, [r0, #{2*k}]"]
        if color: out.append(f"strh r3, [r1, #{2*k}]")
        out += [f"{60+k}:", "add r2, r8"]
    return L(out)
def v6m_fail():
    out = []
    for k in range(U0): out += [f"{30+k}:", "add r10, r11", f"b {60+k}b"]
    return L(out)

# ---- ARMv7E-M
pix = ["ldrh r8, [r0]", "lsr lr, r3, #16", "add r3, r4", "cmp lr, r8"]
PIX = {
    'count': pix + ["itte lo", "strhlo lr, [r0]", "strhlo r5, [r1]", "addhs r7, #1"],
    'plain': pix + ["itt lo", "strhlo lr, [r0]", "strhlo r5, [r1]"],
    'depth': pix + ["it lo", "strhlo lr, [r0]"],
}
def pair(kind, z, c):
    l = ["add r12, r3, r4", "pkhtb lr, r12, r3, asr #16", "add r3, r12, r4",
         f"usub16 r12, lr, {z}", f"sel {z}, {z}, lr"]
    if kind != 'depth': l.append(f"sel {c}, {c}, r5")
    if kind == 'count': l += ["sel r12, r6, r5", "usada8 r7, r12, r5, r7"]
    return l
def quad(kind):
    if kind == 'depth':
        return ["ldrd r8, r9, [r0]"] + pair(kind, 'r8', None) + pair(kind, 'r9', None) + ["strd r8, r9, [r0], #8"]
    return (["ldrd r8, r9, [r0]", "ldrd r10, r11, [r1]"] + pair(kind, 'r8', 'r10') + pair(kind, 'r9', 'r11')
            + ["strd r8, r9, [r0], #8", "strd r10, r11, [r1], #8"])
def pair_single(kind):
    if kind == 'depth':
        return ["ldr r8, [r0]"] + pair(kind, 'r8', None) + ["str r8, [r0], #4"]
    return ["ldr r8, [r0]", "ldr r10, [r1]"] + pair(kind, 'r8', 'r10') + ["str r8, [r0], #4", "str r10, [r1], #4"]
def m4_loop(kind):
    l = [f"subs r2, #{U4}", "blo 4f", "3:"]
    for _ in range(U4 // 4): l += quad(kind)
    l += [f"subs r2, #{U4}", "bhs 3b", "4:"]
    out = L(l)
    if U4 == 8:
        out += [I + '"lsls r2, r2, #30", // C = remainder bit 2, N = bit 1']
        out += L(["bcc 5f"] + quad(kind) + ["5:", "bpl 6f"] + pair_single(kind) + ["6:"])
        out += [I + '"lsls r2, r2, #2", // C = remainder bit 0']
        out += L(["bcc 7f"] + PIX[kind] + ["7:"])
    else:
        out += [I + '"lsls r2, r2, #31", // C = remainder bit 1, N = bit 0']
        out += L(["bcc 5f"] + pair_single(kind) + ["5:", "bpl 6f"] + PIX[kind] + ["6:"])
    return out

sub = {
    'PIXEL_COUNT': L(PIX['count']), 'PIXEL': L(PIX['plain']), 'DPIXEL': L(PIX['depth']),
    'M4_LOOP_COUNT': m4_loop('count'), 'M4_LOOP': m4_loop('plain'), 'M4_LOOP_DEPTH': m4_loop('depth'),
    'V6M_COLOR': v6m_blocks(True), 'V6M_COLOR_NOCOUNT': v6m_blocks(False),
    'V6M_FAIL': v6m_fail(), 'V6M_DEPTH': v6m_blocks(False, color=False),
}
for k, v in sub.items():
    t = t.replace('@' + k + '@', '\n'.join(v))
sh = {8: 29, 16: 28}[U0]
t = t.replace('@V6M_SH@', str(sh)).replace('@V6M_STEP@', str(2 * U0))
t = t.replace('@U4@', str(U4)).replace('@U0@', str(U0))
assert '@' not in t.replace('"@', '').replace("'@", ''), [l for l in t.split('\n') if '@' in l][:5]
open(os.path.join(here, '..', 'kern', 'src', 'span.rs'), 'w').write(t)
print(f"span.rs: M4 unroll {U4}, ARMv6-M unroll {U0}")
