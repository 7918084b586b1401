"""Spline curves, arc length, frames, sweeps and subdivision surfaces, with numpy arrays.

Points are ``(n, 2)`` or ``(n, 3)`` float64 arrays; meshes are ``(vertices (V, 3) float64,
faces)`` with faces ``(F, k)`` int64 when every face has ``k`` corners, else a pair
``(indices, offsets)`` (``offsets`` has ``F + 1`` entries from 0). Errors are ``ValueError``
with the library's messages, and ``OSError`` (``FileNotFoundError``, …) for files.
"""

from os import PathLike
from typing import Literal, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str
DEFAULT_ACCURACY: float
DEFAULT_STEPS: int

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]
ArrayLike = npt.ArrayLike
Path = Union[str, "PathLike[str]"]
Faces = Union[Ints, Tuple[Ints, Ints]]
Creases = Tuple[ArrayLike, ArrayLike]
FrameKind = Literal["rmf", "sequential", "frenet", "zup"]
Scheme = Literal["loop", "catmull-clark", "sqrt3", "doo-sabin", "butterfly", "bilinear"]

class Curve:
    """A curve in 2D or 3D; ``u`` runs over ``[0, num_segments]``."""

    @staticmethod
    def bezier(points: ArrayLike, closed: bool = False, *, steps: int = 20) -> Curve:
        """Piecewise cubic Bézier: ``3m + 1`` points (closed: ``3m``) make ``m`` segments."""
    @staticmethod
    def bspline(points: ArrayLike, closed: bool = False, *, steps: int = 20) -> Curve:
        """Uniform cubic B-spline: ``n ≥ 4`` points, ``n − 3`` segments (closed: ``n ≥ 3``, ``n``)."""
    @staticmethod
    def catmull_rom(points: ArrayLike, closed: bool = False, alpha: float = 0.0, *, steps: int = 20) -> Curve:
        """Catmull-Rom spline; ``alpha`` 0 uniform, 0.5 centripetal, 1 chordal."""
    @staticmethod
    def hermite(points: ArrayLike, tangents: ArrayLike, closed: bool = False, *, steps: int = 20) -> Curve:
        """Cubic Hermite spline through ``points`` with ``tangents`` (``dP/du``)."""
    @staticmethod
    def kochanek_bartels(
        points: ArrayLike,
        tension: Union[None, float, ArrayLike] = None,
        continuity: Union[None, float, ArrayLike] = None,
        bias: Union[None, float, ArrayLike] = None,
        closed: bool = False,
        *,
        steps: int = 20,
    ) -> Curve:
        """Kochanek–Bartels (TCB) spline: ``tension``, ``continuity``, ``bias`` in [−1, 1], per key or one for all."""
    @staticmethod
    def bessel_overhauser(points: ArrayLike, closed: bool = False, *, steps: int = 20) -> Curve:
        """Bessel–Overhauser spline: tangents of chord-length parabolas through each key and its neighbours."""
    @staticmethod
    def bezier_n(points: ArrayLike, *, steps: int = 20) -> Curve:
        """One Bézier curve of degree ``n − 1`` (2 to 64 points)."""
    @staticmethod
    def nurbs(
        points: ArrayLike,
        weights: Optional[ArrayLike] = None,
        degree: int = 3,
        knots: Optional[ArrayLike] = None,
        closed: bool = False,
        *,
        steps: int = 20,
    ) -> Curve:
        """NURBS of ``degree``; default weights 1, clamped uniform knots; closed: periodic."""
    @staticmethod
    def circle(radius: float, *, steps: int = 20) -> Curve:
        """The exact circle of ``radius`` about the origin in the xy-plane (2D)."""
    @staticmethod
    def helix(radius: float, pitch: float, turns: float, *, steps: int = 20) -> Curve:
        """A helix about +z from ``(radius, 0, 0)``, rising ``pitch`` per turn (3D)."""
    @staticmethod
    def trefoil(size: float, *, steps: int = 20) -> Curve:
        """The trefoil knot of ``size`` (closed, 3D)."""
    def with_steps(self, steps: int) -> Curve:
        """This curve with ``steps`` steps per segment."""
    @property
    def name(self) -> Optional[str]: ...
    @property
    def kind(self) -> str:
        """The SWP keyword: ``bez2``, ``bsp3``, ``cr2``, ``her3``, ``nurbs2``, ``circ``, …"""
    @property
    def dim(self) -> int: ...
    @property
    def closed(self) -> bool: ...
    @property
    def steps(self) -> int: ...
    @property
    def num_segments(self) -> int: ...
    @property
    def domain(self) -> Tuple[float, float]: ...
    @property
    def points(self) -> Floats:
        """Control points ``(n, dim)``."""
    @overload
    def evaluate(self, u: float) -> Floats: ...
    @overload
    def evaluate(self, u: ArrayLike) -> Floats: ...
    def evaluate(self, u):
        """Positions: ``(dim,)`` for a number, ``u.shape + (dim,)`` for an array."""
    def derivative(self, u: Union[float, ArrayLike], order: int = 1) -> Floats:
        """``dᵏP/duᵏ`` for order 0 to 3, shaped as ``evaluate``."""
    @overload
    def curvature(self, u: float) -> float: ...
    @overload
    def curvature(self, u: ArrayLike) -> Floats: ...
    def curvature(self, u):
        """Curvature ``|P′ × P″| / |P′|³`` (``inf`` at a cusp)."""
    def arclen(self, accuracy: float = 1e-9) -> float:
        """Length to within ``accuracy`` (absolute)."""
    def arclen_table(self, samples: int = 5, method: Literal["chord", "gauss3"] = "chord") -> Tuple[Floats, Floats]:
        """The u–s table ``(u, s)``, ``samples`` rows per segment."""
    @overload
    def inv_arclen(self, s: float, accuracy: float = 1e-9) -> float: ...
    @overload
    def inv_arclen(self, s: ArrayLike, accuracy: float = 1e-9) -> Floats: ...
    def inv_arclen(self, s, accuracy=1e-9):
        """``u`` with ``|s(u) − s| ≤ accuracy``; ``s`` clamped to ``[0, length]``."""
    def resample(self, spacing: float) -> Floats:
        """Points every ``spacing`` of arc length, ``(k, dim)``."""
    def flatten(
        self,
        tolerance: Optional[float] = None,
        angle_tolerance: Optional[float] = None,
        steps: Optional[int] = None,
    ) -> Tuple[Floats, Floats]:
        """Polyline ``(u, points)``: within ``tolerance`` (distance), by ``angle_tolerance``
        (degrees), or ``steps`` per segment; at most one, default the curve's steps."""
    def frames(self, u: Union[float, ArrayLike], kind: FrameKind = "rmf") -> Tuple[Floats, Floats, Floats]:
        """Frames ``(T, N, B)``, each ``(k, 3)`` (``(3,)`` for a number)."""

class Surface:
    """A surface of an SWP file."""

    @property
    def kind(self) -> str: ...
    @property
    def curves(self) -> list[str]: ...
    def mesh(self, tolerance: Optional[float] = None, *, normals: bool = False) -> Tuple[Floats, ...]:
        """``(vertices, faces)`` (and ``normals``) as ``splinekit sweep`` makes it."""

class Document:
    """An SWP file's curves and surfaces, by name in file order."""

    @property
    def curves(self) -> dict[str, Curve]: ...
    @property
    def surfaces(self) -> dict[str, Surface]: ...

def read_swp(path: Path) -> Document:
    """Reads an SWP file."""

def read_mesh(path: Path, *, creases: bool = False) -> Tuple:
    """``(vertices, faces)`` of an OBJ, PLY, STL or glb file (with ``creases=True`` also the
    OBJ crease tags ``(edges, sharpness)``)."""

def write_mesh(
    path: Path,
    vertices: ArrayLike,
    faces: Union[ArrayLike, Tuple[ArrayLike, ArrayLike]],
    normals: Optional[ArrayLike] = None,
    creases: Optional[Creases] = None,
) -> None:
    """Writes OBJ, PLY, STL or glb (by extension), atomically."""

def sweep(
    profile: Curve,
    path: Curve,
    scale: Union[None, Curve, float, Tuple[float, float]] = None,
    twist: Union[None, Curve, float] = None,
    frames: FrameKind = "rmf",
    caps: bool = True,
    tolerance: Optional[float] = None,
    *,
    align: Literal["origin", "centre", "center", "start"] = "origin",
    join: Literal["mitre", "miter", "round", "bevel"] = "mitre",
    mitre_limit: float = 4.0,
    scale_mode: Literal["multiply", "override"] = "multiply",
    normals: bool = False,
) -> Tuple[Floats, ...]:
    """A 2D ``profile`` swept along ``path``: ``(vertices, faces)`` (and ``normals``)."""

def revolve(
    profile: Curve, slices: int = 32, tolerance: Optional[float] = None, *, normals: bool = False
) -> Tuple[Floats, ...]:
    """A 2D ``profile`` turned about the y axis: ``(vertices, faces)`` (and ``normals``)."""

def subdivide(
    vertices: ArrayLike,
    faces: Union[ArrayLike, Tuple[ArrayLike, ArrayLike]],
    levels: int,
    scheme: Scheme = "loop",
    weights: Literal["loop", "warren"] = "loop",
    boundary: Literal["smooth", "corners"] = "smooth",
    creases: Optional[Creases] = None,
    limit: bool = False,
) -> Tuple[Floats, Faces]:
    """``levels`` levels of ``scheme``: ``(vertices, faces)``."""

def limit_normals(
    vertices: ArrayLike,
    faces: Union[ArrayLike, Tuple[ArrayLike, ArrayLike]],
    scheme: Literal["loop", "catmull-clark"] = "loop",
    weights: Literal["loop", "warren"] = "loop",
    boundary: Literal["smooth", "corners"] = "smooth",
    creases: Optional[Creases] = None,
) -> Floats:
    """Unit limit-surface normals, one per vertex ``(V, 3)``."""
