"""``python -m reports.cli``: the ``bouncer`` command."""

import sys

from reports.cli import main

sys.exit(main())
