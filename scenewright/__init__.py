"""scenewright: procedural 3D scenes from a graph grammar, described in true English.

The pipeline (see DESIGN.md): a rules file is parsed into a grammar
(``scenewright.generator``), expanded into a scene graph, laid out by MCMC
(``scenewright.generator.layout``), then described (``scenewright.describer``),
rendered and exported (``scenewright.render``).
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("scenewright")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0"

from scenewright.api import generate, load_rules
from scenewright.scene import Scene

__all__ = ["Scene", "__version__", "generate", "load_rules"]
