"""Learning from example scenes: a rule set's numbers re-estimated from what the
examples drew (``weights``) and written back into its text (``rewrite``); which object
types the examples relate (``relations``, with its poses, statistics, tests, fixed
arrangements, results and pruning in ``relation_*``); and a whole rule set induced from
examples alone (``induce``, its records in ``induction``, written by ``rules_text``,
checked by ``learn``)."""
