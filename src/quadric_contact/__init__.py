"""quadric-contact: exact and certified contact detection between an ellipsoid
and another quadric, after Brozos-Vázquez, Pereira-Sáez, Rodríguez-Raposo,
Souto-Salorio and Tarrío-Tobar, *Contact detection between a small ellipsoid
and another quadric*, Computer Aided Geometric Design 98 (2022).
"""

from __future__ import annotations

from .classification import QuadricKind
from .contact import transversal_contact
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
from .motions import RigidMotion, rotation_from_quaternion
from .pencil import CharacteristicPolynomial, characteristic_polynomial
from .plane import plane_side
from .quadric import Quadric
from .regions import ROOT_SIGN_TABLE, relative_position
from .results import ContactResult, PlaneSideResult, Region, RegionResult

__version__ = "0.1.0"

__all__ = [
    "ROOT_SIGN_TABLE",
    "CharacteristicPolynomial",
    "ContactResult",
    "DegeneratePencilError",
    "EquationError",
    "ExcludedQuadricError",
    "NonFiniteError",
    "NotANumberError",
    "NotAPlaneError",
    "NotAnEllipsoidError",
    "NotRationalError",
    "NotSymmetricError",
    "PlaneSideResult",
    "Quadric",
    "QuadricContactError",
    "QuadricKind",
    "Region",
    "RegionResult",
    "RigidMotion",
    "RootSigns",
    "RootStructure",
    "ShapeError",
    "UndecidedError",
    "__version__",
    "characteristic_polynomial",
    "discrimination_sequence",
    "paper_deltas",
    "plane_side",
    "relative_position",
    "root_signs",
    "root_structure",
    "rotation_from_quaternion",
    "transversal_contact",
]
