"""Scenes: the model (:mod:`quadric_contact.scenes.scene_model`) and its TOML reader
(:mod:`quadric_contact.scenes.scene_toml`), under one name.

The scene format is described in :mod:`quadric_contact.scenes.scene_toml`.
"""

from __future__ import annotations

from quadric_contact.scenes.scene_model import (
    EFFECTS,
    EXCLUDED_KINDS,
    THEOREM_2_EFFECTS,
    MovingEllipsoid,
    Scene,
    SmallnessCheck,
)
from quadric_contact.scenes.scene_toml import (
    builtin_scene,
    builtin_scene_names,
    load_scene,
    parse_scene,
)

__all__ = [
    "EFFECTS",
    "EXCLUDED_KINDS",
    "THEOREM_2_EFFECTS",
    "MovingEllipsoid",
    "Scene",
    "SmallnessCheck",
    "builtin_scene",
    "builtin_scene_names",
    "load_scene",
    "parse_scene",
]
