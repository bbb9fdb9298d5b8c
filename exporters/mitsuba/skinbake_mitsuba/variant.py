"""Choosing a Mitsuba 3 variant, and the LLVM library the llvm_* variants need.

Dr.Jit's LLVM back end needs libLLVM 16 or newer: Debian 12's libLLVM 14/15 abort
with "Cannot select fmaximum" on the first kernel. Debian 12 has libllvm19
(scripts/setup.sh installs it). DRJIT_LIBLLVM_PATH must be set before mitsuba
is imported; without a usable libLLVM the scalar_* variants are used (slow).
"""
import glob
import os
import re

_LLVM_GLOBS = ("/usr/lib/llvm-*/lib/libLLVM-*.so*", "/usr/lib/x86_64-linux-gnu/libLLVM-*.so*",
               "/usr/lib/aarch64-linux-gnu/libLLVM-*.so*", "/usr/lib/libLLVM-*.so*")
LLVM_MIN_MAJOR = 16


def find_libllvm():
    """Path of the newest libLLVM with major version >= 16, or None."""
    best = None
    for pattern in _LLVM_GLOBS:
        for path in glob.glob(pattern):
            m = re.search(r"libLLVM-(\d+)", os.path.basename(path))
            if not m or int(m.group(1)) < LLVM_MIN_MAJOR:
                continue
            key = (int(m.group(1)), -len(path))
            if best is None or key > best[0]:
                best = (key, path)
    return best[1] if best else None


def setup_llvm():
    """Point Dr.Jit at a usable libLLVM (unless the user did); True when one is set."""
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return True
    path = find_libllvm()
    if path is None:
        return False
    os.environ["DRJIT_LIBLLVM_PATH"] = path
    return True


def choose(kind, want=None):
    """Set and return a variant: kind is 'mono', 'rgb' or 'spectral'.

    want names a variant explicitly; otherwise llvm_ad_KIND when libLLVM >= 16
    exists, else scalar_KIND (scalar_mono does not exist: scalar_rgb is used with
    grey values instead)."""
    have_llvm = setup_llvm()
    import mitsuba as mi
    if want is None:
        if have_llvm and "llvm_ad_" + kind in mi.variants():
            want = "llvm_ad_" + kind
        elif "scalar_" + kind in mi.variants():
            want = "scalar_" + kind
        else:
            want = "scalar_rgb"
    mi.set_variant(want)
    # Mitsuba logs to stdout: keep stdout for results (warnings are kept out too).
    mi.set_log_level(mi.LogLevel.Error)
    return want
