"""Composing: English in, a scene out (docs/compose.md)."""
