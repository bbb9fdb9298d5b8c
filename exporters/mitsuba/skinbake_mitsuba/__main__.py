"""python -m skinbake_mitsuba COMMAND ...: see --help."""
import sys

from . import cli

sys.exit(cli.main(sys.argv[1:]))
