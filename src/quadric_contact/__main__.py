"""``python -m quadric_contact`` is the ``quadric-contact`` command."""

import sys

from .cli import main

sys.exit(main())
