"""Writes the hand-made seeds of fuzz/corpus/bands/ (the named ones; the others are
inputs libFuzzer kept). Layout as `harness::bands` reads it: width, height, band rows,
a flags byte (cull, shading, bins, light), bin junk, [light], the view, the shape byte,
then mesh operations. Run: python3 fuzz/gen_bands_seeds.py"""
import os, struct, random
HERE = os.path.dirname(os.path.abspath(__file__))
def u16(v): return struct.pack('<H', v & 0xffff)
out = {}
def seed(name, w, h, rows, cull, shade, binmode, light, view, shape, ops, junk=0xAAAA):
    # shade: 0 flat, 1 lambert, 2 gouraud (as the harness decodes the flags byte)
    kind = lambda f: 0 if (f//3)%8 <= 3 else (1 if (f//3)%8 <= 6 else 2)
    flags = next(f for f in range(256) if f%3 == cull and kind(f) == shade
                 and (f>>5)&3 == binmode and (f>>7) == (1 if light else 0))
    b = bytes([w-1, h-1, rows-1, flags]) + u16(junk)
    if light: b += light
    b += view + bytes([shape]) + ops
    out[name] = b
def vert(x,y,z): return u16(x)+u16(y)+u16(z)
def orbit(yaw, pitch, dist, fov): return bytes([0, yaw, pitch & 0xff, dist, fov])
def fl(v): return bytes([1]) + u16(int(round(v*64)))
r = random.Random(1)
col = lambda: bytes([r.randrange(256) for _ in range(3)])
# A floor of 3×3 tiles in y = 0 (shift 3, scale 1/1024: 0.3 units a tile), each
# tile split again along the other diagonal and some triangles repeated.
S = 8*300
floor = b''
for z in range(3):
    for x in range(3):
        a = (x*S-3*S//2, 0, z*S-3*S//2); b=(a[0]+S,0,a[2]); c=(a[0]+S,0,a[2]+S)
        floor += bytes([3]) + vert(*a)+vert(*b)+vert(*c) + col()
for q in range(9):
    floor += bytes([6, q]) + col()
for f in range(0, 18, 3):
    floor += bytes([5 + 8*(f%3), f]) + col()
FLOOR = (4<<3)|3
seed('floor_flat_bins', 48, 40, 7, 0, 0, 1, None, orbit(140, 40, 70, 40), FLOOR, floor)
seed('floor_lambert_nobins', 33, 29, 1, 2, 1, 0, None, orbit(100, 60, 60, 30), FLOOR, floor)
seed('floor_below_slack', 40, 40, 40, 1, 1, 3, None, orbit(10, -50, 80, 20), FLOOR, floor)
persp = bytes([2]) + b''.join(fl(v) for v in [0.3, 0.8, 0.9, 0, 0, 0, 60, 0.05, 20])
seed('floor_persp', 20, 16, 2, 0, 0, 1, None, persp, FLOOR, floor, junk=0x1234)
# A soup of triangles with repeats (rotated) and triangles of shared vertices.
soup = b''
for i in range(12):
    soup += bytes([0]) + b''.join(vert(r.randrange(-20000,20000),r.randrange(-20000,20000),r.randrange(-20000,20000)) for _ in range(3)) + col()
for i in range(8):
    soup += bytes([5 + 8*r.randrange(3), r.randrange(12)]) + col()
for i in range(5):
    soup += bytes([7]) + u16(r.randrange(65536))+u16(r.randrange(65536))+u16(r.randrange(65536)) + col()
SOUP = (5<<3)|5
seed('soup_short_bins', 40, 40, 5, 1, 0, 2, None, orbit(30, 20, 40, 40), SOUP, soup)
light = b''.join(fl(v) for v in [-1, 1, 0.5, 0.2, 0.8])
seed('soup_light_bins', 24, 47, 3, 1, 1, 1, light, orbit(200, 10, 90, 70), SOUP, soup)
seed('soup_clipped', 32, 32, 4, 0, 0, 1, None, orbit(77, 5, 0, 100), (4<<3)|3, soup)
for k,v in out.items():
    open(os.path.join(HERE, 'corpus', 'bands', k), 'wb').write(v); print(k, len(v))
