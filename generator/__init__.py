"""Rules language, grammar expansion, scene graphs and the MCMC layout."""
