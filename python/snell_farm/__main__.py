"""``python -m snell_farm``: the same as the ``snell-farm`` command."""

import sys

from .cli import main

sys.exit(main())
