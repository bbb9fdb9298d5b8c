#!/usr/bin/env python3
"""Writes the PNG seeds of tests/fuzz/corpus/png that skinbake itself does
not produce: palette, low bit depths, grey+alpha, transparency, Adam7
interlacing (the reader must handle every legal PNG).  Run from this folder;
the files are committed, so this is documentation more than a build step."""
import struct, zlib

def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)

def png(w, h, depth, ctype, rows, extra=b'', interlace=0):
    ihdr = struct.pack('>IIBBBBB', w, h, depth, ctype, 0, 0, interlace)
    raw = b''.join(b'\0' + r for r in rows)
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + extra +
            chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))

def adam7_rows(w, h, bpp, pix):
    """Rows of the seven Adam7 passes, each row prefixed later by png()."""
    passes = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]
    rows = []
    for x0, y0, dx, dy in passes:
        for y in range(y0, h, dy):
            r = b''.join(pix(x, y) for x in range(x0, w, dx))
            if r:
                rows.append(r)
    return rows

seeds = {
    # 2-bit palette, 4 x 3, with a tRNS entry
    'seed-palette-2bit.png': png(4, 3, 2, 3, [bytes([0b00011011]), bytes([0b11100100]), bytes([0b01010101])],
                                 chunk(b'PLTE', bytes([0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255])) +
                                 chunk(b'tRNS', bytes([0, 255]))),
    # 1-bit grey, 8 x 2
    'seed-gray-1bit.png': png(8, 2, 1, 0, [bytes([0xa5]), bytes([0x5a])]),
    # 16-bit grey+alpha, 2 x 2, with a tEXt value skinbake reads
    'seed-gray-alpha-16.png': png(2, 2, 16, 4, [bytes(range(8)), bytes(range(8, 16))],
                                  chunk(b'tEXt', b'skinbake:tile_mm\x008')),
    # 8-bit RGBA, 3 x 1, zTXt comment
    'seed-rgba-8.png': png(3, 1, 8, 6, [bytes(range(12))], chunk(b'zTXt', b'Comment\x00\x00' + zlib.compress(b'hi'))),
    # 8-bit grey, 9 x 9, Adam7 interlaced
    'seed-gray-interlaced.png': png(9, 9, 8, 0, adam7_rows(9, 9, 1, lambda x, y: bytes([(x * 9 + y) & 255])),
                                    interlace=1),
}
for name, data in seeds.items():
    with open('corpus/png/' + name, 'wb') as f:
        f.write(data)
