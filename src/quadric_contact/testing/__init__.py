"""Testing support: hypothesis strategies, hard cases, random samples."""
