"""Rules language, grammar expansion, scene graphs and the MCMC layout."""

from .expand import expand
from .graph_export import graph_to_dot
from .rules import Rules, check_rules, indoor_catalog, load_rules, shipped_rule_sets
from .rules_errors import Diagnostic, ExpansionError, RulesError, format_diagnostics

__all__ = [
    "Diagnostic",
    "ExpansionError",
    "Rules",
    "RulesError",
    "check_rules",
    "expand",
    "format_diagnostics",
    "graph_to_dot",
    "indoor_catalog",
    "load_rules",
    "shipped_rule_sets",
]
