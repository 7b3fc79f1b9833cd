"""Meshes, offscreen previews and glTF export of laid-out scenes."""
