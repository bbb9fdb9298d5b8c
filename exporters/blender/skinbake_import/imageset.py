"""Reading an image set: manifest.json checked against the schema (schema.py), every file's
structure checked (imagefiles.py), then the images loaded into Blender at the stated sizes."""
import hashlib
import math
import os

import bpy

from . import schema
from .common import ImageSetError, json_load
from .imagefiles import check_exr, check_png
from .schema import CHANNELS, PNG_TYPES


def _need(d, key, kind, where):
    if key not in d:
        raise ImageSetError(f"{where}: missing \"{key}\"")
    v = d[key]
    if kind is float and isinstance(v, int) and not isinstance(v, bool):
        v = float(v)
    if not isinstance(v, kind):
        raise ImageSetError(f"{where}: \"{key}\" is {v!r}, expected {kind.__name__}")
    return v


def read_manifest(directory):
    """Parse and check DIR/manifest.json; returns the dict."""
    directory = os.path.abspath(directory)
    if not os.path.isdir(directory):
        raise ImageSetError(f"{directory}: no such image-set directory")
    path = os.path.join(directory, "manifest.json")
    if not os.path.isfile(path):
        raise ImageSetError(f"{path}: missing (not a skinbake image set; write one with "
                            "`skinbake export blender`)")
    try:
        with open(path, encoding="utf-8") as f:
            m = json_load(f)
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise ImageSetError(f"{path}: unreadable or not JSON ({e})") from None
    if not isinstance(m, dict) or m.get("format") != schema.FORMAT:
        raise ImageSetError(f"{path}: \"format\" is not \"{schema.FORMAT}\"")
    ver = m.get("format_version")
    if ver not in schema.FORMAT_VERSIONS:
        raise ImageSetError(f"{path}: format_version {ver!r} is not supported by import_skin.py "
                            f"{schema.VERSION} (supported: {', '.join(map(str, schema.FORMAT_VERSIONS))})")
    _check_sums(m, directory, path)
    for key, (lo, hi) in schema.NUMBERS.items():
        _number(m, key, lo, hi, path)
    for key, hi in schema.TRIPLES.items():
        v = _need(m, key, list, path)
        if len(v) != 3 or not all(_is_number(x) and 0 <= x <= hi for x in v):
            raise ImageSetError(f"{path}: \"{key}\" is {v!r}, expected 3 numbers in [0, {hi:g}]")
    files = _need(m, "files", dict, path)
    for role in schema.FILES:
        e = _need(files, role, dict, f"{path}: files")
        _need(e, "path", str, f"{path}: files.{role}")
        for key in ("width", "height"):
            _number(e, key, *schema.FILE_PIXELS, f"{path}: files.{role}", int)
        p = os.path.join(directory, e["path"])
        if os.path.dirname(os.path.normpath(e["path"])) != "" or os.path.isabs(e["path"]):
            raise ImageSetError(f"{path}: files.{role}: \"path\" is {e['path']!r}, expected a file name in the set")
        if not os.path.isfile(p) or os.path.getsize(p) == 0:
            raise ImageSetError(f"{p}: missing or empty (listed in manifest.json as {role})")
        if p.lower().endswith(".exr"):
            check_exr(p, e["width"], e["height"], CHANNELS.get(e.get("channels")), f"files.{role}.channels")
        else:
            check_png(p, e["width"], e["height"], PNG_TYPES.get(e.get("channels")), f"files.{role}.channels")
    lut = _need(m, "brdf_lut", dict, path)
    nc, nphi = _need(lut, "cos_nodes", int, f"{path}: brdf_lut"), _need(lut, "phi_nodes", int, f"{path}: brdf_lut")
    if nc < 2 or nphi < 2 or files["brdf_lut"]["width"] != nc * nphi or files["brdf_lut"]["height"] != nc:
        raise ImageSetError(f"{path}: brdf_lut {nc} x {nphi} nodes does not match files.brdf_lut size")
    ex = _need(m, "exact", dict, path)
    s = _need(ex, "sun_direction", list, f"{path}: exact")
    if len(s) != 3 or not all(_is_number(x) for x in s) or s[2] <= 0:
        raise ImageSetError(f"{path}: exact.sun_direction is {s!r}, expected 3 numbers with z > 0")
    if "sun_strength_w_m2" in ex:
        _number(ex, "sun_strength_w_m2", *schema.SUN_STRENGTH_W_M2, f"{path}: exact")
    d = _need(m, "detail", dict, path)
    if not _need(d, "flat", bool, f"{path}: detail"):
        _number(d, "tile_mm", *schema.TILE_MM, f"{path}: detail")
        if "mean_normal_z" in d:
            _number(d, "mean_normal_z", *schema.MEAN_NORMAL_Z, f"{path}: detail")
    if "general_fit" in m:
        _check_fit(_need(m, "general_fit", dict, path), f"{path}: general_fit")
    if "family" in m:
        _check_family(m, directory, path, nc, nphi)
    m["_dir"] = directory
    return m


def _check_sums(m, directory, path):
    """Each file the manifest's "checksums" lists (skinbake writes it: {"NAME": "sha256:HEX"}) still
    has that SHA-256: a file changed or damaged since the export is refused before it is used.
    Sets from before the checksums have none; nothing to check then."""
    sums = m.get("checksums")
    if sums is None:
        return
    if not isinstance(sums, dict):
        raise ImageSetError(f"{path}: \"checksums\" is {sums!r}, expected an object of \"FILE\": \"sha256:HEX\"")
    for name, want in sums.items():
        if not isinstance(want, str) or not want.startswith("sha256:") or len(want) != 71 or \
                os.path.isabs(name) or ".." in name:
            raise ImageSetError(f"{path}: checksums.{name} is {want!r}, expected a file of the set with "
                                "\"sha256:\" and 64 hex digits")
        p = os.path.join(directory, name)
        try:
            with open(p, "rb") as f:
                have = "sha256:" + hashlib.sha256(f.read()).hexdigest()
        except OSError as e:
            raise ImageSetError(f"{p}: {e.strerror} (listed in manifest.json checksums)") from None
        if have != want:
            raise ImageSetError(f"{p} has changed since its manifest was written ({have} there, {want} "
                                "expected): the file was edited or damaged; export the set again")


def _is_number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def _number(d, key, lo, hi, where, kind=float):
    """d[key]: a finite number (an integer for kind int) in [lo, hi]."""
    v = _need(d, key, kind, where)
    if not _is_number(v) or not lo <= v <= hi:
        raise ImageSetError(f"{where}: \"{key}\" is {v!r}, expected a number in [{lo:g}, {hi:g}]")
    return v


def _check_fit(f, where):
    """The fitted mixture of the general mode: nodes ascending in [0, 1], an RGB triple of numbers
    >= 0 per node for both colours, roughnesses in [0, 1], an index in [1, 3]."""
    nodes = _need(f, "cos_view_nodes", list, where)
    if len(nodes) < 2 or not all(_is_number(x) and 0 <= x <= 1 for x in nodes) or \
            any(b <= a for a, b in zip(nodes, nodes[1:])):
        raise ImageSetError(f"{where}: \"cos_view_nodes\" is {nodes!r}, expected at least 2 ascending numbers "
                            "in [0, 1]")
    for key in schema.FIT_RGB:
        v = _need(f, key, list, where)
        if len(v) != len(nodes) or not all(isinstance(c, list) and len(c) == 3 and
                                           all(_is_number(x) and x >= 0 for x in c) for c in v):
            raise ImageSetError(f"{where}: \"{key}\" is not {len(nodes)} RGB triples of numbers >= 0 "
                                "(one per cos_view_nodes)")
    for key, (lo, hi) in schema.FIT_NUMBERS.items():
        if key in f or key not in schema.FIT_OPTIONAL:
            _number(f, key, lo, hi, where)



def _check_family(m, directory, path, nc, nphi):
    """The family section of a set with parameter maps (`export blender --family --maps`)."""
    fam = _need(m, "family", dict, path)
    where = f"{path}: family"
    counts = _need(fam, "sub_counts", list, where)
    if len(counts) != 3 or not all(isinstance(n, int) and n >= 1 for n in counts):
        raise ImageSetError(f"{where}: \"sub_counts\" must be 3 integers >= 1, got {counts!r}")
    slices = _need(fam, "slices", int, where)
    if slices != counts[0] * counts[1] * counts[2]:
        raise ImageSetError(f"{where}: slices {slices} is not the product of sub_counts {counts}")
    files = _need(fam, "files", dict, where)
    size = None
    for role in schema.FAMILY_FILES:
        e = _need(files, role, dict, f"{where}.files")
        for key, kind in (("file", str), ("width", int), ("height", int)):
            _need(e, key, kind, f"{where}.files.{role}")
        p = os.path.join(directory, e["file"])
        if not os.path.isfile(p) or os.path.getsize(p) == 0:
            raise ImageSetError(f"{p}: missing or empty (listed in manifest.json as family {role})")
        check_exr(p, e["width"], e["height"])
        if role != "family_lut":
            if size not in (None, (e["width"], e["height"])):
                raise ImageSetError(f"{p}: {e['width']}x{e['height']} px, the other maps are {size[0]}x{size[1]}")
            size = (e["width"], e["height"])
    lut = files["family_lut"]
    if (lut["width"], lut["height"]) != (nc * nphi, nc * slices):
        raise ImageSetError(f"{where}: family_lut is {lut['width']}x{lut['height']} px, expected "
                            f"{nc * nphi}x{nc * slices} ({slices} slices of the brdf_lut layout)")



def load_image(m, role, data=True):
    """Load one file of the set and check Blender read it at the size the manifest states."""
    e = m["files"][role]
    p = os.path.join(m["_dir"], e["path"])
    try:
        img = bpy.data.images.load(p, check_existing=True)
    except RuntimeError as err:
        raise ImageSetError(f"{p}: Blender cannot read it ({err})") from None
    if data:                    # PNGs default to sRGB: data maps must not be converted
        img.colorspace_settings.name = "Non-Color"
    w, h = img.size
    if (w, h) != (e["width"], e["height"]):
        bpy.data.images.remove(img)
        raise ImageSetError(f"{p}: Blender read {w}x{h} px, manifest.json says "
                            f"{e['width']}x{e['height']} (corrupt or replaced file)")
    return img


def load_family_image(m, role):
    """One of the family files (float EXR data), checked as load_image checks."""
    e = m["family"]["files"][role]
    return load_image({"files": {role: dict(e, path=e["file"])}, "_dir": m["_dir"]}, role)
