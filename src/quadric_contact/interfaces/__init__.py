"""Plotting, animation, benchmarking and the command line."""
