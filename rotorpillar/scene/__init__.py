"""The scene: one structure and what to run on it, read from TOML.

Rooms: :mod:`.words` (the project's word lists), :mod:`.sections` (the
sections as frozen dataclasses; the machine's in :mod:`.machine`, a field's
declaration in :mod:`.fields`), :mod:`.validation` (checks, building, new scenes from typed values),
:mod:`.files` (TOML files, embedded scenes, ``--set``); every public name is
re-exported here.

A scene file has one table per section below; every quantity is a float in
SI units (m, kg, s, N, Pa, rad), stated once in the field's docstring.  Each
field carries its allowed range, so validation, the one-line error message and
the documentation all come from the same place.

>>> s = load_scene("paper")
>>> s.pillar.height, s.shaft.stiffness
(20.0, 400000.0)
>>> with_values(s, {"shaft.stiffness": 5e6}).shaft.stiffness
5000000.0

A scene is a value: :func:`with_values` derives a new one from typed values,
each checked as a scene file's; :func:`override` takes ``--set`` text, for the
command line.
"""

from .fields import param
from .files import (
    apply_overrides,
    embedded_scenes,
    load_scene,
    override,
    parse_assignment,
    read_scene_toml,
    read_text_file,
    what_is_there,
)
from .sections import (
    EXCITATION_KINDS,
    FABRICATION_CLASSES,
    MODAL_SOURCES,
    OPTIONAL_SECTIONS,
    PLANES,
    RECORD_UNITS,
    REDUCTION_SOURCES,
    SECTIONS,
    TOP_MASSES,
    TOP_MODELS,
    Converge,
    Drive,
    Excitation,
    FullOrder,
    Gondola,
    Load,
    Material,
    Mesh,
    Modal,
    ModalModel,
    Pillar,
    Reduction,
    Rotor,
    Scene,
    SceneError,
    Shaft,
    Simulate,
    Sweep,
)
from .tower import FOUNDATION_KINDS, Can, Foundation, Reference, Segment, segment_index
from .validation import SCENE_NAME, check_combinations, check_field, scene_from_dict, with_values
from .words import (
    ADAPTIVE_INTEGRATORS,
    CASES,
    CELL_TYPES,
    FIXED_STEP_INTEGRATORS,
    FULL_ORDER_MODELS,
    INTEGRATORS,
    MODELS,
    SCIPY_METHODS,
    SHELL_CELL_TYPES,
    STUDY_CASES,
    STUDY_MODELS,
)

__all__ = [
    "ADAPTIVE_INTEGRATORS",
    "CASES",
    "CELL_TYPES",
    "Can",
    "Converge",
    "Drive",
    "EXCITATION_KINDS",
    "Excitation",
    "FABRICATION_CLASSES",
    "FOUNDATION_KINDS",
    "FIXED_STEP_INTEGRATORS",
    "FULL_ORDER_MODELS",
    "Foundation",
    "FullOrder",
    "Gondola",
    "INTEGRATORS",
    "Load",
    "MODAL_SOURCES",
    "MODELS",
    "Material",
    "Mesh",
    "Modal",
    "ModalModel",
    "OPTIONAL_SECTIONS",
    "PLANES",
    "Pillar",
    "RECORD_UNITS",
    "REDUCTION_SOURCES",
    "Reference",
    "Reduction",
    "Rotor",
    "SCENE_NAME",
    "SCIPY_METHODS",
    "SECTIONS",
    "SHELL_CELL_TYPES",
    "STUDY_CASES",
    "STUDY_MODELS",
    "Scene",
    "Segment",
    "SceneError",
    "check_combinations",
    "check_field",
    "Shaft",
    "Simulate",
    "Sweep",
    "TOP_MASSES",
    "TOP_MODELS",
    "apply_overrides",
    "embedded_scenes",
    "load_scene",
    "override",
    "param",
    "parse_assignment",
    "read_scene_toml",
    "read_text_file",
    "scene_from_dict",
    "segment_index",
    "what_is_there",
    "with_values",
]
