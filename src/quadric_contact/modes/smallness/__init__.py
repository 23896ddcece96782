"""Smallness on stacks (Tables 1-2, corrected): the tables as data and their evaluation in
each number system."""
