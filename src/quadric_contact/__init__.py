"""quadric-contact: exact and certified contact detection between an ellipsoid
and another quadric, after Brozos-Vázquez, Pereira-Sáez, Rodríguez-Raposo,
Souto-Salorio and Tarrío-Tobar, *Contact detection between a small ellipsoid
and another quadric*, Computer Aided Geometric Design 98 (2022).

The top level is the public API: the types (``Quadric``, ``RealAlgebraic``, the
pencil and its invariants, parametric families), the predicates (one meaning for
every input form and number mode), their results, codes and errors, and the
scenes.  Tables and internals live in their layers: the formulas in
``quadric_contact._generated``, exact arithmetic in ``quadric_contact.exact``,
the model in ``quadric_contact.model``, the paper's decisions and tables in
``quadric_contact.theory``, the number modes in ``quadric_contact.modes``, what
the paper prints in ``quadric_contact.paper``, testing support in
``quadric_contact.testing``.
"""

from __future__ import annotations

from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.exact.descartes import RootSigns, root_signs
from quadric_contact.exact.discriminants import (
    RootStructure,
    discrimination_sequence,
    paper_deltas,
    root_structure,
)
from quadric_contact.exact.errors import (
    ChoiceError,
    DegeneratePencilError,
    EquationError,
    ExcludedQuadricError,
    MissingDependencyError,
    NonFiniteError,
    NotAnEllipsoidError,
    NotANumberError,
    NotAPlaneError,
    NotRationalError,
    NotSymmetricError,
    ProofsNotFoundError,
    QuadricContactError,
    SceneError,
    SchedulerError,
    ShapeError,
    UndecidedError,
    WorkLimitError,
)
from quadric_contact.families.family import Family, family
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.invariants import QuadricInvariants, invariants
from quadric_contact.model.motions import RigidMotion, rotation_from_quaternion
from quadric_contact.model.quadric import Quadric
from quadric_contact.modes import (
    ContactCode,
    ContactKindCode,
    CriterionCode,
    OverlapCode,
    RegionCode,
    SmallnessCode,
)
from quadric_contact.modes.distances import contact_scale, distance
from quadric_contact.modes.predicates import (
    CriterionResult,
    contact_kind,
    corollary_10,
    overlap,
    plane_side,
    relative_position,
    smallness,
    transversal_contact,
)
from quadric_contact.modes.stacks.packing import Packed, pack, symmetrize, unpack
from quadric_contact.scenes.composite import Composite, Piece
from quadric_contact.scenes.scene_model import MovingEllipsoid, Scene
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names, load_scene, parse_scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.simulation_reports import SimulationResult
from quadric_contact.theory.contact_kind import ContactAnalysis, ContactKind, analyze_contact
from quadric_contact.theory.contact_scale import ContactScaleResult
from quadric_contact.theory.distance import DistanceResult
from quadric_contact.theory.geometric import GeometricDecision, decide_geometrically
from quadric_contact.theory.overlap import OverlapResult, TouchingError
from quadric_contact.theory.pencil import CharacteristicPolynomial, characteristic_polynomial
from quadric_contact.theory.regions import ROOT_SIGN_TABLE
from quadric_contact.theory.results import (
    ContactResult,
    PlaneSideResult,
    Region,
    RegionResult,
)
from quadric_contact.theory.segre import SegreSymbol, segre_symbol
from quadric_contact.theory.smallness import SmallnessReport

__version__ = "0.1.0"

__all__ = [
    "ROOT_SIGN_TABLE",
    "CharacteristicPolynomial",
    "ChoiceError",
    "Composite",
    "ContactAnalysis",
    "ContactCode",
    "ContactKind",
    "ContactKindCode",
    "ContactResult",
    "ContactScaleResult",
    "CriterionCode",
    "CriterionResult",
    "DegeneratePencilError",
    "DistanceResult",
    "EquationError",
    "ExcludedQuadricError",
    "Family",
    "GeometricDecision",
    "MissingDependencyError",
    "MovingEllipsoid",
    "NonFiniteError",
    "NotANumberError",
    "NotAPlaneError",
    "NotAnEllipsoidError",
    "NotRationalError",
    "NotSymmetricError",
    "OverlapCode",
    "OverlapResult",
    "Packed",
    "Piece",
    "PlaneSideResult",
    "ProofsNotFoundError",
    "Quadric",
    "QuadricContactError",
    "QuadricInvariants",
    "QuadricKind",
    "RealAlgebraic",
    "Region",
    "RegionCode",
    "RegionResult",
    "RigidMotion",
    "RootSigns",
    "RootStructure",
    "Scene",
    "SceneError",
    "SchedulerError",
    "SegreSymbol",
    "ShapeError",
    "SimulationResult",
    "SmallnessCode",
    "SmallnessReport",
    "TouchingError",
    "UndecidedError",
    "WorkLimitError",
    "__version__",
    "analyze_contact",
    "builtin_scene",
    "builtin_scene_names",
    "characteristic_polynomial",
    "contact_kind",
    "contact_scale",
    "corollary_10",
    "decide_geometrically",
    "discrimination_sequence",
    "distance",
    "family",
    "invariants",
    "load_scene",
    "overlap",
    "pack",
    "paper_deltas",
    "parse_scene",
    "plane_side",
    "relative_position",
    "root_signs",
    "root_structure",
    "rotation_from_quaternion",
    "segre_symbol",
    "simulate",
    "smallness",
    "symmetrize",
    "transversal_contact",
    "unpack",
]
