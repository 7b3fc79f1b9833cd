"""``python -m scenewright.cli``: the ``scenewright`` command."""

from scenewright.cli import run

run()
