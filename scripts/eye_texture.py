"""The eyes of the MakeHuman model with their own colours (scripts/demo.sh): the model's
brown_eye.png has red-brown irises and pink sclerae, which render as red eyes.  This keeps its
detail (the luminance of every texel) and gives the irises a chosen colour and the sclerae a
near-neutral white:

    python eye_texture.py IN.png OUT.png [R,G,B]      (iris colour, linear, default hazel)

The iris discs are where the texture has them: centres (0.703, 0.298) and (0.288, 0.708) of
the image, radius 0.118 (measured on brown_eye.png of assimp-testmodels).  Needs numpy."""
import os
import struct
import sys
import zlib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "lib"))
from images import read_png  # noqa: E402

IRISES = ((0.703, 0.298), (0.288, 0.708))
IRIS_R = 0.118


def write_png(path, a):
    h, w, c = a.shape
    raw = b"".join(b"\0" + a[y].tobytes() for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6 if c == 4 else 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def main():
    src, dst = sys.argv[1], sys.argv[2]
    tint = np.array([float(x) for x in sys.argv[3].split(",")] if len(sys.argv) > 3 else (0.30, 0.20, 0.09))
    w, h, ch, bits, rows, _ = read_png(src)
    a = np.array(rows, dtype=np.float64).reshape(h, w, ch)[:, :, :3] / (65535.0 if bits == 16 else 255.0)
    lin = np.where(a <= 0.04045, a / 12.92, ((a + 0.055) / 1.055) ** 2.4)
    lum = lin @ np.array([0.2126, 0.7152, 0.0722])
    yy, xx = np.mgrid[0:h, 0:w]
    d = np.min([np.hypot(xx / w - cx, yy / h - cy) for cx, cy in IRISES], axis=0) / IRIS_R
    iris = np.clip((1.06 - d) / 0.12, 0.0, 1.0)[:, :, None]      # soft rim
    t = tint / (tint @ np.array([0.2126, 0.7152, 0.0722]))
    coloured = np.clip(lum[:, :, None] * 1.6 * t, 0.0, 1.0)           # the iris, brighter than the red one
    white = lum[:, :, None] * np.array([1.0, 0.99, 0.97]) + 0.15 * (lin - lum[:, :, None])
    out = iris * coloured + (1 - iris) * white
    enc = np.where(out <= 0.0031308, out * 12.92, 1.055 * np.clip(out, 0, 1) ** (1 / 2.4) - 0.055)
    rgb = np.clip(np.round(enc * 255), 0, 255).astype(np.uint8)
    if ch == 4:                 # keep the model's alpha (POV-Ray reads the texture with it)
        alpha = np.array(rows, dtype=np.float64).reshape(h, w, ch)[:, :, 3:] / (257.0 if bits == 16 else 1.0)
        rgb = np.concatenate([rgb, np.round(alpha).astype(np.uint8)], axis=2)
    write_png(dst, rgb)


if __name__ == "__main__":
    main()
