"""``python -m quadric_contact`` is the ``quadric-contact`` command."""

import sys

from quadric_contact.interfaces.cli import main

sys.exit(main())
