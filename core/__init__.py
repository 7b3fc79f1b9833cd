"""The core data model every stage reads and none imports upward from.

``scenewright.core`` depends on no pipeline stage (``generator``, ``describer``,
``render``) and on nothing of the application layer (``scenewright.api``, the CLI,
datasets). It holds what the stages pass between them: the relation registry
(``relations``), the scene graph (``scene_graph``), the laid-out scene and its poses
(``scene``, ``poses``), the object frame convention (``frames``), the shape registry
(``shapes``), the seeded random streams (``seeds``), bounded reading of the user's
files (``files``), the bounds every input must keep (``limits``), the two kinds of
error a user can meet (``errors``), and what every stage that writes or checks output
shares: files written whole or not at all (``atomic``), the scene.json schema and its
checks (``schema_check``), and the wall time per stage (``timing``). ``VERSION`` is the
package's version, which scene.json and the other outputs record (pyproject.toml reads
it from here).
"""

VERSION = "0.1.0"
