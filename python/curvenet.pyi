"""Type stubs of the curvenet module (python/curvenet_module.cpp documents each call).

Copies: C-contiguous float64 arrays (uv, control points) are read in place, any other array-like is
converted once; evaluate_positions writes into its result (or into out=); an Evaluation's fields are
views of one (N, 4, 3) or (N, 7, 3) array; a Mesh is copied once from the model. The GIL is released
during every engine call."""

import os
from typing import Any, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
Float64Array = npt.NDArray[np.float64]
UInt32Array = npt.NDArray[np.uint32]
CurveInput = Union[ArrayLike, dict[str, Any]]
Side = Union[int, tuple[int, float, float]]

class Error(ValueError):
    """A failed call: str() is 'file: element: reason'."""

    code: str
    """'invalid-argument', 'invalid-input', 'out-of-domain', 'buffer-too-small', 'no-mesh', 'internal',
    'out-of-memory'."""
    file: str
    element: str
    """Where: 'curve 3', 'face 0 side 2', 'point 17'; empty when not known."""

class Evaluation:
    """Surface points with exact first derivatives; the fields are (N, 3) views of one array."""

    @property
    def points(self) -> Float64Array: ...
    @property
    def du(self) -> Float64Array: ...
    @property
    def dv(self) -> Float64Array: ...
    @property
    def normals(self) -> Float64Array: ...
    def __len__(self) -> int: ...

class Evaluation2(Evaluation):
    """An Evaluation with second derivatives."""

    @property
    def duu(self) -> Float64Array: ...
    @property
    def duv(self) -> Float64Array: ...
    @property
    def dvv(self) -> Float64Array: ...

class Mesh:
    """A triangle mesh with exact vertex normals."""

    vertices: Float64Array
    """(V, 3) positions."""
    normals: Float64Array
    """(V, 3) unit normals."""
    triangles: UInt32Array
    """(T, 3) vertex indices, counter-clockwise seen from the normal side."""
    face_triangle_start: UInt32Array
    """(F + 1,): the triangles of face f are face_triangle_start[f] up to face_triangle_start[f + 1]."""

class Model:
    """A curve network and the transfinite surfaces over its faces."""

    @staticmethod
    def load(source: str | os.PathLike[str], scheme: str = "gregory-g1", edge_curvature: str | None = None,
             master_faces: str | None = None) -> Model:
        """'builtin:NAME' or a network file (.json, .lop), every face with `scheme`."""
    @staticmethod
    def build(curves: Sequence[CurveInput], faces: Sequence[Sequence[Side]], scheme: str = "gregory-g1",
              tolerance: float = 1e-7, name: str = "") -> Model:
        """Curves as (P, 3) Bézier control points or dict(points, degree, knots, weights); faces as loops
        of sides, each a curve index (the whole curve) or (curve, from, to)."""
    @property
    def face_count(self) -> int: ...
    @property
    def curve_count(self) -> int: ...
    @property
    def surface_count(self) -> int: ...
    @property
    def source(self) -> str: ...
    @property
    def last_edited_faces(self) -> list[int]: ...
    def domain_sides(self, face: int) -> int: ...
    def domain_corners(self, face: int) -> Float64Array:
        """(n, 2) corners of the face's domain polygon."""
    def face_scheme(self, face: int) -> str: ...
    def has_exact_second_derivatives(self, face: int) -> bool: ...
    def set_face_options(self, face: int | None = None, scheme: str = "gregory-g1",
                         edge_curvature: str | None = None, master_faces: str | None = None) -> None: ...
    def set_control_points(self, curve: int, points: ArrayLike) -> None: ...
    def evaluate_positions(self, face: int, uv: ArrayLike, threads: int = 0,
                           out: Float64Array | None = None) -> Float64Array:
        """(N, 3) positions at the (N, 2) domain points uv: the fast path."""
    def evaluate(self, face: int, uv: ArrayLike, threads: int = 0) -> Evaluation: ...
    def evaluate_second_order(self, face: int, uv: ArrayLike, threads: int = 0, step: float = 1e-5) -> Evaluation2: ...
    def tessellate(self, resolution: int = 16, threads: int = 0, face: int | None = None) -> Mesh: ...
    def check(self, scheme: str | None = None, samples: int = 64, resolution: int = 32) -> dict[str, Any]:
        """The dict `curvenet check --json` prints."""
    def render(self, mode: str = "reflection", size: tuple[int, int] = (640, 480), resolution: int = 32,
               view: tuple[float, float] = (30.0, 30.0), stripes: float = 8.0, boundaries: bool = False,
               threads: int = 0) -> npt.NDArray[np.uint8]:
        """(height, width, 3) sRGB picture."""

def builtins() -> list[str]: ...
def bench(source: str = "builtin:pentagon", resolution: int = 256, points: int = 4000,
          threads: int = 0) -> dict[str, Any]:
    """The dict `curvenet bench --json` prints."""
