"""Turns a laid-out scene into grammatical English that is true of it."""
