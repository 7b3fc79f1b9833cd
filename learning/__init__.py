"""Learning from example scenes: a rule set's numbers re-estimated from what the
examples drew (``weights``) and written back into its text (``rewrite``)."""
