# import_skin.py: the command line of the skinbake importer, whose code is the package
# skinbake_import beside this file (also the Blender extension and add-on: see README.md).
#
#   blender -b [FILE.blend] --python-exit-code 1 --python exporters/blender/import_skin.py -- SET \
#       [--mode general|exact] [--objects A,B] [--render F.exr] [--save F.blend] ...
#
# Bad input prints "import_skin.py: error: ..." and exits with status 2.  Imported as a module
# (tests do), it offers the package's functions under the same names as before the split.
import os
import sys

sys.dont_write_bytecode = True          # no __pycache__ next to the sources
_here = os.path.dirname(os.path.abspath(__file__))
if _here not in sys.path:
    sys.path.insert(0, _here)

from skinbake_import import *  # noqa: E402,F401,F403
from skinbake_import import __version__, bl_info, run  # noqa: E402,F401

if __name__ == "__main__":
    run(sys.argv)
