"""``python -m quadric_contact.codegen``: regenerate the generated code (or check it)."""

import sys

from quadric_contact.codegen.command import main

if __name__ == "__main__":
    sys.exit(main())
