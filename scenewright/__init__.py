"""scenewright: procedural 3D scenes from a graph grammar, described in true English.

The pipeline (README.md, "How it works"): a rules file is parsed into a grammar
(``scenewright.generator``), expanded into a scene graph, laid out by MCMC
(``scenewright.generator.layout``), then described (``scenewright.describer``),
rendered and exported (``scenewright.render``); ``write_scene`` writes a scene's folder
as ``scenewright generate`` does.
"""

from scenewright.core import VERSION as __version__

__all__ = [
    "Scene",
    "__version__",
    "compose",
    "describe",
    "export",
    "generate",
    "load_rules",
    "render_image",
    "write_scene",
]

#: The public names and the modules they come from. They are imported on first use, so
#: that ``scenewright --help`` (and a Ctrl-C during start-up) does not wait for numpy
#: and networkx.
_PUBLIC = {
    "Scene": "scenewright.core.scene",
    "compose": "scenewright.api",
    "describe": "scenewright.api",
    "export": "scenewright.api",
    "generate": "scenewright.api",
    "load_rules": "scenewright.api",
    "render_image": "scenewright.api",
    "write_scene": "scenewright.scene_folder",
}


def __getattr__(name: str):
    if name in _PUBLIC:
        import importlib

        value = getattr(importlib.import_module(_PUBLIC[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'scenewright' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_PUBLIC))
