"""scenewright: procedural 3D scenes from a graph grammar, described in true English.

The pipeline (see DESIGN.md): a rules file is parsed into a grammar
(``scenewright.generator``), expanded into a scene graph, laid out by MCMC
(``scenewright.generator.layout``), then described (``scenewright.describer``),
rendered and exported (``scenewright.render``).
"""

from scenewright.api import describe, export, generate, load_rules, render_image
from scenewright.core import VERSION as __version__
from scenewright.core.scene import Scene

__all__ = ["Scene", "__version__", "describe", "export", "generate", "load_rules", "render_image"]
