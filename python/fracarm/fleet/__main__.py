"""python -m fracarm.fleet: the fracarm-fleet CLI."""
import sys

from .cli import main

sys.exit(main())
