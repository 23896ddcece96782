"""The paper's decisions on exact quadrics (Theorems 2, 5, 13, 14; Tables 1-4)."""
