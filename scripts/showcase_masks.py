# Masks for the maps showcase (scripts/render-maps-showcase.sh), run by Blender:
#   blender -b --factory-startup --python scripts/showcase_masks.py -- MODEL OUT_DIR SIZE
# Imports the MakeHuman model (a .zae zip or its .dae), and paints three 8-bit grey masks in the
# UV space of its body mesh (human-baseMesh), SIZE x SIZE texels, from 3-D regions of the face:
# lips.png (an ellipse around the mouth, fading over its outer half and in depth: no outline),
# cheeks.png (two flushes fading over their radius), nose.png (the tip and the wings), ears.png
# (both ears), freckles.png (160 spots of 1-2 mm radius, strengths 0.45-1, over the nose and upper
# cheeks, from vertices picked by a fixed seed). A fourth argument lists the masks to paint (default the five above);
# `brows` paints brows.png, which only then is made: two arched bands above the eyes, 8 mm tall at
# the inner end and 3.6 mm at the outer, fading at both ends and over half their height (scripts/demo.sh
# tints the skin's melanin through it: no hair).  scripts/demo.sh reads the copies in
# scenes/masks/ (made with SIZE 2048).  Landmarks were measured on the model in Blender's frame (z up, face toward -y): nose tip
# (0, -0.160, 1.516) m, upper lip at z 1.495, lower lip at z 1.480, mouth 5 cm wide.
import bpy, math, os, random, struct, sys, zipfile, zlib, tempfile

argv = sys.argv[sys.argv.index('--') + 1:]
model, out, size = argv[0], argv[1], int(argv[2])
only = argv[3].split(',') if len(argv) > 3 else None
if model.endswith('.zae'):
    tmp = tempfile.mkdtemp()
    with zipfile.ZipFile(model) as z:
        z.extractall(tmp)
    model = os.path.join(tmp, [n for n in os.listdir(tmp) if n.endswith('.dae')][0])
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.collada_import(filepath=model)
ob = [o for o in bpy.data.objects if o.type == 'MESH' and 'base' in o.name.lower()][0]
me = ob.data
me.calc_loop_triangles()
mw = ob.matrix_world
P = [tuple(mw @ v.co) for v in me.vertices]
uv = me.uv_layers.active.data

def smooth(d):  # 1 inside, 0 outside, smooth between d = 0.7 and 1
    return 1.0 if d <= 0.7 else 0.0 if d >= 1 else 0.5 + 0.5 * math.cos(math.pi * (d - 0.7) / 0.3)

def ramp(t):  # 0 at t <= 0, 1 at t >= 1, a cosine between
    return 0.0 if t <= 0 else 1.0 if t >= 1 else 0.5 - 0.5 * math.cos(math.pi * t)

def lips(p):  # full inside half the ellipse, fading over the rest and 10 mm in depth (no outline)
    x, y, z = p
    d = math.sqrt((x / 0.027) ** 2 + ((z - 1.4875) / 0.0145) ** 2)
    return ramp((1.05 - d) / 0.55) * ramp((-0.122 - y) / 0.010)

def soft(d):  # a flush: 1 at the centre, fading over the whole radius (no visible rim)
    return 0.0 if d >= 1 else (0.5 + 0.5 * math.cos(math.pi * d)) ** 1.5

def cheeks(p):
    x, y, z = p
    if y > -0.06:
        return 0.0
    return soft(math.sqrt(((abs(x) - 0.048) / 0.034) ** 2 + ((z - 1.505) / 0.03) ** 2))

def nose(p):
    x, y, z = p
    if y > -0.12:
        return 0.0
    return smooth(math.sqrt((x / 0.021) ** 2 + ((y + 0.152) / 0.03) ** 2 + ((z - 1.513) / 0.02) ** 2))

def ears(p):  # head half-width 0.0835 m at the ears; measured on the model
    x, y, z = p
    if abs(x) < 0.066:
        return 0.0
    return smooth(math.sqrt(((abs(x) - 0.08) / 0.016) ** 2 + ((y + 0.005) / 0.032) ** 2 + ((z - 1.535) / 0.042) ** 2))

rng = random.Random(15)
cand = [p for p in P if abs(p[0]) < 0.065 and 1.50 < p[2] < 1.56 and p[1] < -0.105]
spots = []
for _ in range(160):  # ephelides 2-4 mm across (radius 1-2 mm), of varied strength
    c = rng.choice(cand)
    c = (c[0] + rng.uniform(-0.003, 0.003), c[1], c[2] + rng.uniform(-0.003, 0.003))
    spots.append((c, rng.uniform(0.0010, 0.0020), rng.uniform(0.45, 1.0)))

def freckles(p):
    best = 0.0
    for c, r, a in spots:
        d = math.dist(p, c) / r
        if d < 1:
            best = max(best, a * (0.5 + 0.5 * math.cos(math.pi * d)))
    return best

def brows(p):  # eyes: x 0.0135..0.0444, z 1.539..1.569 (their mesh); brows from x 10 to 56 mm
    x, y, z = p
    t = (abs(x) - 0.010) / 0.046
    if t <= 0 or t >= 1 or y > -0.08:
        return 0.0
    zc = 1.562 + 0.008 * math.sin(math.pi * (0.15 + 0.75 * t))  # arched, highest 2/5 outward
    h = 0.0040 * (1 - 0.55 * t)
    return ramp(t / 0.12) * ramp((1 - t) / 0.25) * ramp((1 - abs(z - zc) / h) / 0.5) * ramp((-0.085 - y) / 0.01)

masks = {'lips': lips, 'cheeks': cheeks, 'nose': nose, 'ears': ears, 'freckles': freckles}
if only:
    masks = {k: f for k, f in dict(masks, brows=brows).items() if k in only}
img = {k: bytearray(size * size) for k in masks}
for t in me.loop_triangles:
    ps = [P[i] for i in t.vertices]
    if max(p[2] for p in ps) < 1.42 or (min(p[1] for p in ps) > -0.05 and max(abs(p[0]) for p in ps) < 0.066):
        continue  # far from the face and the ears
    us = [uv[l].uv for l in t.loops]
    xs = [u[0] * size - 0.5 for u in us]
    ys = [(1 - u[1]) * size - 0.5 for u in us]
    det = (xs[1] - xs[0]) * (ys[2] - ys[0]) - (xs[2] - xs[0]) * (ys[1] - ys[0])
    if abs(det) < 1e-12:
        continue
    for py in range(max(0, math.floor(min(ys))), min(size - 1, math.ceil(max(ys))) + 1):
        for px in range(max(0, math.floor(min(xs))), min(size - 1, math.ceil(max(xs))) + 1):
            b1 = ((px - xs[0]) * (ys[2] - ys[0]) - (xs[2] - xs[0]) * (py - ys[0])) / det
            b2 = ((xs[1] - xs[0]) * (py - ys[0]) - (px - xs[0]) * (ys[1] - ys[0])) / det
            b0 = 1 - b1 - b2
            if min(b0, b1, b2) < -0.02:
                continue
            p = tuple(b0 * ps[0][k] + b1 * ps[1][k] + b2 * ps[2][k] for k in range(3))
            for k, f in masks.items():
                v = int(round(255 * f(p)))
                if v > img[k][py * size + px]:
                    img[k][py * size + px] = v

def png(path, w, h, data):
    raw = b''.join(b'\0' + bytes(data[y * w:(y + 1) * w]) for y in range(h))
    ch = lambda t, d: struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
    open(path, 'wb').write(b'\x89PNG\r\n\x1a\n' + ch(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0)) +
                           ch(b'IDAT', zlib.compress(raw, 6)) + ch(b'IEND', b''))

os.makedirs(out, exist_ok=True)
for k in masks:
    png(os.path.join(out, k + '.png'), size, size, img[k])
    print('showcase_masks.py: %s.png %d texels painted' % (k, sum(1 for v in img[k] if v)))
