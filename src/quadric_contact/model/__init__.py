"""The model: exact quadrics, the equation parser, classification, invariants, rigid motions."""
