"""Image files as the tests and scripts read them back (and test pictures written), with the
standard library only (python3 without numpy): PNG (8 or 16 bits, gray, RGB or RGBA, every
filter, tEXt) and OpenEXR (scanline float32, compression NONE, ZIPS or ZIP: what skinbake writes).

    sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
    from images import read_png, read_exr, write_png
"""
import struct
import zlib

PNG_CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}     # colour type -> channels


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else b if pb <= pc else c


def read_png(path):
    """(w, h, channels, bits, rows, text): rows[y][x] is a tuple of the channels' integer
    values, row 0 at the top; text holds the tEXt chunks."""
    d = open(path, "rb").read()
    assert d[:8] == b"\x89PNG\r\n\x1a\n", path + ": not a PNG file"
    pos, idat, text = 8, b"", {}
    while pos < len(d):
        n, kind = struct.unpack(">I4s", d[pos:pos + 8])
        body = d[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, bits, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body[:13])
            assert interlace == 0 and bits in (8, 16), path + ": interlaced or not 8/16 bits"
        elif kind == b"IDAT":
            idat += body
        elif kind == b"tEXt":
            k, v = body.split(b"\0", 1)
            text[k.decode()] = v.decode("latin-1")
    ch = PNG_CHANNELS[ctype]
    bpp = ch * bits // 8
    stride = w * bpp
    raw = zlib.decompress(idat)
    prev = bytearray(stride)
    rows = []
    fmt = ">%dH" % ch if bits == 16 else "%dB" % ch
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                line[i] = (line[i] + _paeth(a, b, c)) & 255
        rows.append([struct.unpack(fmt, bytes(line[x * bpp:(x + 1) * bpp])) for x in range(w)])
        prev = line
    return w, h, ch, bits, rows, text


def read_exr(path):
    """{channel: rows} of a scanline float32 OpenEXR file, row 0 at the top."""
    b = open(path, "rb").read()
    assert b[:4] == b"\x76\x2f\x31\x01", path + ": not an OpenEXR file"
    p, attrs = 8, {}
    while b[p] != 0:
        e = b.index(b"\0", p)
        name = b[p:e].decode()
        p = e + 1
        e = b.index(b"\0", p)
        typ = b[p:e].decode()
        p = e + 1
        (n,) = struct.unpack_from("<i", b, p)
        p += 4
        attrs[name] = (typ, b[p:p + n])
        p += n
    p += 1
    ch, q, v = [], 0, attrs["channels"][1]
    while v[q] != 0:
        e = v.index(b"\0", q)
        ch.append((v[q:e].decode(), struct.unpack_from("<i", v, e + 1)[0]))
        q = e + 17
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    w, h, comp = x1 - x0 + 1, y1 - y0 + 1, attrs["compression"][1][0]
    lpc = {0: 1, 2: 1, 3: 16}[comp]      # scanlines per chunk: NONE, ZIPS, ZIP
    offs = struct.unpack_from("<%dQ" % ((h + lpc - 1) // lpc), b, p)
    out = {c: [None] * h for c, _ in ch}
    for o in offs:
        y, n = struct.unpack_from("<ii", b, o)
        d = b[o + 8:o + 8 + n]
        lines = min(lpc, y1 + 1 - y)
        if comp and n < lines * w * 4 * len(ch):
            t = bytearray(zlib.decompress(d))
            for i in range(1, len(t)):
                t[i] = (t[i - 1] + t[i] - 128) & 0xff
            half = (len(t) + 1) // 2
            u = bytearray(len(t))
            u[0::2] = t[:half]
            u[1::2] = t[half:]
            d = bytes(u)
        q = 0
        for r in range(lines):
            for c, typ in ch:
                assert typ == 2, path + ": float32 channels only"
                out[c][y - y0 + r] = struct.unpack_from("<%df" % w, d, q)
                q += 4 * w
    return out


def write_png(path, w, h, ch, f, bits=8):
    """A W x H PNG of CH channels (gray, gray+alpha, RGB, RGBA) and BITS (8 or 16) per
    sample, unfiltered, sample values f(x, y) in [0, 1] (clamped)."""
    top = 255 if bits == 8 else 65535
    rows = []
    for y in range(h):
        r = b'\0'
        for x in range(w):
            for v in f(x, y):
                q = max(0, min(top, round(top * v)))
                r += bytes([q]) if bits == 8 else struct.pack('>H', q)
        rows.append(r)
    ct = {1: 0, 2: 4, 3: 2, 4: 6}[ch]

    def chunk(t, b):
        return struct.pack('>I', len(b)) + t + b + struct.pack('>I', zlib.crc32(t + b) & 0xffffffff)
    with open(path, 'wb') as fp:
        fp.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, bits, ct, 0, 0, 0))
                 + chunk(b'IDAT', zlib.compress(b''.join(rows))) + chunk(b'IEND', b''))
