"""Parametric families of pairs: the paper's conditions over Q(parameters)."""
