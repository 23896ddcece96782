"""The exact layer: rationals, precision, linear algebra, real algebraic numbers, root signs."""
