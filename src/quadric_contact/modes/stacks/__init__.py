"""Stacks and pairs: array input, its validation, its packed and integer forms, the rows a stack uses."""
