"""The structure of the image set's OpenEXR and PNG files, checked byte by byte before Blender
reads them (no bpy here)."""
import struct
import zlib

from .common import ImageSetError
from .schema import CHANNELS, PNG_TYPES

# Blender's readers can hang on a truncated EXR (measured with 3.4.1: a 300-byte albedo.exr made
# it spin forever) and accept some damaged files silently, so every file is checked here first.
_EXR_LINES = {0: 1, 1: 1, 2: 1, 3: 16, 4: 32, 5: 16, 6: 32, 7: 32, 8: 32, 9: 256}


def _read_bytes(path):
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as e:
        raise ImageSetError(f"{path}: {e.strerror}") from None




def _exr_channels(raw):
    """(name, pixel type) of an EXR chlist attribute."""
    out, pos = [], 0
    while pos < len(raw) and raw[pos] != 0:
        end = raw.index(b"\0", pos)
        out.append((raw[pos:end].decode("latin-1"), struct.unpack_from("<i", raw, end + 1)[0]))
        pos = end + 1 + 16
    return out


def check_exr(path, width, height, channels=(), key="channels"):
    """Structure of a single-part scanline EXR: header, size, channels (float32 with the names the
    manifest's channels promise, when given), and every chunk inside the file."""
    b = _read_bytes(path)
    bad = lambda why: ImageSetError(f"{path}: corrupt OpenEXR file ({why})")   # noqa: E731
    if len(b) < 8 or b[:4] != b"\x76\x2f\x31\x01":
        raise bad("no OpenEXR magic number")
    if struct.unpack_from("<I", b, 4)[0] & 0x1a00:
        raise bad("tiled, deep or multi-part: expected one scanline part")
    pos, attrs = 8, {}
    try:
        while b[pos] != 0:
            name_end = b.index(b"\0", pos)
            type_end = b.index(b"\0", name_end + 1)
            (size,) = struct.unpack_from("<i", b, type_end + 1)
            start = type_end + 5
            if size < 0 or start + size > len(b):
                raise bad("attribute runs past the end")
            attrs[b[pos:name_end].decode("latin-1")] = b[start:start + size]
            pos = start + size
        pos += 1
        x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"])
        comp = attrs["compression"][0]
        chans = _exr_channels(attrs["channels"])
    except (IndexError, KeyError, ValueError, struct.error):
        raise bad("truncated or incomplete header") from None
    if (x1 - x0 + 1, y1 - y0 + 1) != (width, height):
        raise ImageSetError(f"{path}: {x1 - x0 + 1}x{y1 - y0 + 1} px, manifest.json says {width}x{height}")
    if channels is None:
        raise ImageSetError(f"{path}: manifest.json {key} is not one of {', '.join(CHANNELS)}")
    if channels != () and tuple(n for n, _ in chans) != channels or any(t != 2 for _, t in chans):
        raise ImageSetError(f"{path}: channels {', '.join(f'{n} (type {t})' for n, t in chans)}; manifest.json "
                            f"{key} says {','.join(sorted(channels))}, expected exactly those as float32 (type 2)")
    if comp not in _EXR_LINES:
        raise bad(f"unknown compression {comp}")
    chunks = -(-height // _EXR_LINES[comp])
    if pos + 8 * chunks > len(b):
        raise bad("truncated offset table")
    for off in struct.unpack_from(f"<{chunks}Q", b, pos):
        if off + 8 > len(b) or off + 8 + struct.unpack_from("<i", b, off + 4)[0] > len(b):
            raise bad("truncated pixel data")


def check_png(path, width, height, ctype_want=-1, key="channels"):
    """Every chunk's CRC, IHDR size, 16 bits of the colour type the manifest's channels promise (when given), and
    the complete image data of a PNG."""
    b = _read_bytes(path)
    bad = lambda why: ImageSetError(f"{path}: corrupt PNG file ({why})")       # noqa: E731
    if b[:8] != b"\x89PNG\r\n\x1a\n":
        raise bad("no PNG signature")
    pos, idat, ihdr, end = 8, [], None, False
    while pos + 12 <= len(b) and not end:
        (n,) = struct.unpack_from(">I", b, pos)
        kind, data = b[pos + 4:pos + 8], b[pos + 8:pos + 8 + n]
        if len(data) != n or pos + 12 + n > len(b):
            raise bad("truncated chunk")
        if zlib.crc32(kind + data) != struct.unpack_from(">I", b, pos + 8 + n)[0]:
            raise bad(f"CRC error in {kind.decode('latin-1')}")
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", data)
        elif kind == b"IDAT":
            idat.append(data)
        end = kind == b"IEND"
        pos += 12 + n
    if ihdr is None or not end:
        raise bad("no IHDR or IEND")
    w, h, depth, ctype = ihdr[:4]
    if (w, h) != (width, height):
        raise ImageSetError(f"{path}: {w}x{h} px, manifest.json says {width}x{height}")
    chans = {0: 1, 2: 3, 4: 2, 6: 4}.get(ctype)
    if chans is None or depth not in (8, 16) or ihdr[6] != 0:
        raise bad(f"colour type {ctype} at {depth} bits, interlace {ihdr[6]}: not written by skinbake")
    if ctype_want is None:
        raise ImageSetError(f"{path}: manifest.json {key} is not one of {', '.join(PNG_TYPES)}")
    if ctype_want != -1 and (ctype != ctype_want or depth != 16):
        raise ImageSetError(f"{path}: colour type {ctype} at {depth} bits; manifest.json {key} says "
                            f"{[k for k, t in PNG_TYPES.items() if t == ctype_want][0]}, expected colour type "
                            f"{ctype_want} at 16 bits")
    try:
        raw = zlib.decompress(b"".join(idat))
    except zlib.error as e:
        raise bad(f"image data: {e}") from None
    if len(raw) != h * (1 + w * chans * depth // 8):
        raise bad("image data has the wrong size")
