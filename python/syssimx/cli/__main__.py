"""`python -m syssimx.cli`: the command line."""

import sys

from .main import main

if __name__ == "__main__":  # a sweep's worker processes import this module again
    sys.exit(main())
