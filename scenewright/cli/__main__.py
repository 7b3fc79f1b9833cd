"""``python -m scenewright.cli``: the ``scenewright`` command."""

import sys

from scenewright.cli import main

sys.exit(main())
