# The exact composite of make.py's quads by ray casting (independent of the project), against the
# PNGs `starnt render --scene quads.gltf --camera cam.json --method M --width 256 --height 256 --out M.png`
# wrote: `python3 exact.py M...`. Errors in 8-bit sRGB steps; pixels within 0.012 of an edge skipped.
import json, sys, math, zlib, struct
def png(path):
    d = open(path, 'rb').read(); p = 8; idat = b''; w = h = 0
    while p < len(d):
        n, t = struct.unpack('>I4s', d[p:p+8]); c = d[p+8:p+8+n]; p += 12 + n
        if t == b'IHDR': w, h, bd, ct = struct.unpack('>IIBB', c[:10]); ch = {2: 3, 6: 4}[ct]
        elif t == b'IDAT': idat += c
    raw = zlib.decompress(idat); stride = w * ch; out = []; prev = bytearray(stride); i = 0
    for y in range(h):
        f = raw[i]; line = bytearray(raw[i+1:i+1+stride]); i += 1 + stride
        for x in range(stride):
            a = line[x-ch] if x >= ch else 0; b = prev[x]; c = prev[x-ch] if x >= ch else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                pr = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[x] = (line[x] + pr) & 255
        out.append([tuple(line[x*ch:x*ch+3]) for x in range(w)]); prev = line
    return out
def lin(s):
    s /= 255.0
    return s / 12.92 if s <= 0.04045 else ((s + 0.055) / 1.055) ** 2.4
def srgb(l):
    l = min(max(l, 0.0), 1.0)
    return 255 * (12.92 * l if l <= 0.0031308 else 1.055 * l ** (1 / 2.4) - 0.055)
quads = json.load(open('quads.json')); bg = [1.0, 1.0, 1.0]
W = H = 256
cam = json.load(open('cam.json'))
eye = cam['position']
def sub(a, b): return [a[i] - b[i] for i in range(3)]
def norm(a): l = math.sqrt(sum(v*v for v in a)); return [v / l for v in a]
def cross(a, b): return [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]
f = norm(sub(cam['target'], eye)); r = norm(cross(f, cam['up'])); u = cross(r, f)
t = math.tan(math.radians(cam['fov_y_deg']) / 2)
exact = {}; infront = {}
for y in range(H):
    for x in range(W):
        nx = (x + 0.5) / W * 2 - 1; ny = 1 - (y + 0.5) / H * 2
        d = [f[i] + nx * t * r[i] + ny * t * u[i] for i in range(3)]
        hits = []; ok = True
        for q in quads:
            s = (q['z'] - eye[2]) / d[2]; p = [eye[i] + s * d[i] for i in range(3)]
            dx = abs(p[0] - q['c'][0]) - q['h'][0]; dy = abs(p[1] - q['c'][1]) - q['h'][1]
            if abs(dx) < 0.012 or abs(dy) < 0.012: ok = False
            if dx < 0 and dy < 0: hits.append((s, q))
        if not ok: continue
        hits.sort(key=lambda h: h[0])
        c = [0, 0, 0]; T = 1.0; n = 0; blocked = False
        for s, q in hits:
            if q['opaque']:
                c = [c[i] + T * q['col'][i] for i in range(3)]; T = 0; blocked = True; break
            c = [c[i] + T * q['a'] * q['col'][i] for i in range(3)]; T *= 1 - q['a']; n += 1
        exact[(x, y)] = [c[i] + T * bg[i] for i in range(3)]
        infront[(x, y)] = n if blocked else 99
print(f"{len(exact)} interior pixels; errors in 8-bit sRGB steps (of 255) against the exact composite")
for m in sys.argv[1:]:
    img = png(m + '.png'); worst = 0; worst2 = 0; tot = 0; n2 = 0
    for (x, y), e in exact.items():
        err = max(abs(img[y][x][i] - srgb(e[i])) for i in range(3))
        worst = max(worst, err); tot += err
        if infront[(x, y)] <= 2: worst2 = max(worst2, err); n2 += 1
    print(f"{m:16s} max {worst:6.2f}  mean {tot/len(exact):6.3f}  where <= 2 layers lie in front of the opaque quad: max {worst2:6.2f} ({n2} px)")
