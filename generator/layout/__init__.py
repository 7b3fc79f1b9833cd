"""Markov chain Monte Carlo placement of objects and paths (the paper's energy)."""
