"""The number modes as strategies: how each mode computes a sign, never which question it answers."""
