"""Generated code; see :mod:`quadric_contact.codegen`."""
