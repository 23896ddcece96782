"""quadric-contact: exact and certified contact detection between an ellipsoid
and another quadric, after Brozos-Vázquez, Pereira-Sáez, Rodríguez-Raposo,
Souto-Salorio and Tarrío-Tobar, *Contact detection between a small ellipsoid
and another quadric*, Computer Aided Geometric Design 98 (2022).
"""

from __future__ import annotations

from .algebraic import RealAlgebraic
from .classification import QuadricKind
from .contact_kind import ContactAnalysis, ContactKind, analyze_contact
from .descartes import RootSigns, root_signs
from .discriminants import RootStructure, discrimination_sequence, paper_deltas, root_structure
from .errors import (
    DegeneratePencilError,
    EquationError,
    ExcludedQuadricError,
    NonFiniteError,
    NotAnEllipsoidError,
    NotANumberError,
    NotAPlaneError,
    NotRationalError,
    NotSymmetricError,
    QuadricContactError,
    ShapeError,
    UndecidedError,
)
from .family import Family, family
from .geometric import GeometricDecision, decide_geometrically
from .invariants import QuadricInvariants, invariants
from .modes import ContactCode, ContactKindCode, CriterionCode, OverlapCode, RegionCode, SmallnessCode
from .motions import RigidMotion, rotation_from_quaternion
from .overlap import OverlapResult, TouchingError
from .packing import Packed, pack, unpack
from .pencil import CharacteristicPolynomial, characteristic_polynomial
from .predicates import (
    CriterionResult,
    contact_kind,
    corollary_10,
    overlap,
    plane_side,
    relative_position,
    smallness,
    transversal_contact,
)
from .printed_tables import printed_table_2
from .quadric import Quadric
from .regions import ROOT_SIGN_TABLE
from .results import ContactResult, PlaneSideResult, Region, RegionResult
from .segre import SegreSymbol, segre_symbol
from .smallness import SmallnessReport, table_1

__version__ = "0.1.0"

__all__ = [
    "ROOT_SIGN_TABLE",
    "CharacteristicPolynomial",
    "ContactAnalysis",
    "ContactCode",
    "ContactKind",
    "ContactKindCode",
    "ContactResult",
    "CriterionCode",
    "CriterionResult",
    "DegeneratePencilError",
    "EquationError",
    "ExcludedQuadricError",
    "Family",
    "GeometricDecision",
    "NonFiniteError",
    "NotANumberError",
    "NotAPlaneError",
    "NotAnEllipsoidError",
    "NotRationalError",
    "NotSymmetricError",
    "OverlapCode",
    "OverlapResult",
    "Packed",
    "PlaneSideResult",
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
    "SegreSymbol",
    "ShapeError",
    "SmallnessCode",
    "SmallnessReport",
    "TouchingError",
    "UndecidedError",
    "__version__",
    "analyze_contact",
    "characteristic_polynomial",
    "contact_kind",
    "corollary_10",
    "decide_geometrically",
    "discrimination_sequence",
    "family",
    "invariants",
    "overlap",
    "pack",
    "paper_deltas",
    "plane_side",
    "printed_table_2",
    "relative_position",
    "root_signs",
    "root_structure",
    "rotation_from_quaternion",
    "segre_symbol",
    "smallness",
    "table_1",
    "transversal_contact",
    "unpack",
]
