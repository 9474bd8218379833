# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Type hints of the package mrepair (the calls are in the compiled module _mrepair)."""

from os import PathLike
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Vertices = npt.ArrayLike
"""an N x 3 array of real coordinates (float64; other real dtypes are converted)"""
Faces = Union[npt.ArrayLike, Sequence[Sequence[int]]]
"""an integer M x 3 (or M x k) array, or a list of index lists (polygons)"""
FacesOut = Union[npt.NDArray[np.int64], List[List[int]]]
"""an int64 M x 3 array; a list of index lists when some face is not a triangle"""
Report = Dict[str, Any]
"""the report of the matching `mrepair` command (its JSON as a dict)"""
Progress = Optional[Callable[[str, float], Optional[bool]]]
"""None, or progress(phase, fraction in [0, 1]); returning False cancels"""
Result = Tuple[npt.NDArray[np.float64], FacesOut, Report]

__version__: str
DEFECT_REPORT_KEYS: Dict[str, str]
"""kind of locate_defects / defect_overlay -> key of the report's "defects" section"""

class Cancelled(KeyboardInterrupt):
    """raised when a progress callable returns False."""

def read(path: Union[str, PathLike[str]]) -> Tuple[npt.NDArray[np.float64], FacesOut]:
    """reads an OFF, OBJ, PLY or STL file as a polygon soup (V, F).

    Raises OSError when the file cannot be read, ValueError when it is
    malformed, empty, of an unknown kind or has out-of-range indices."""

def write(path: Union[str, PathLike[str]], V: Vertices, F: Faces, *, binary: bool = False) -> None:
    """writes an OFF, OBJ, PLY or STL file (by extension); binary PLY or STL with binary=True."""

def inspect(
    V: Vertices,
    F: Faces,
    *,
    spike_angle: Optional[float] = None,
    small_hole: Optional[int] = None,
    small_component: Optional[int] = None,
    t_junction_tolerance: Optional[float] = None,
    self_intersections: bool = True,
    progress: Progress = None,
) -> Report:
    """counts every defect mrepair fixes and the quality figures (`mrepair inspect --json`).

    None: the library's default (doc/defects.md)."""

def compare_to_reference(
    V: Vertices,
    F: Faces,
    reference: Vertices,
    *,
    tolerance: Optional[float] = None,
) -> Report:
    """how much of `reference` (the vertices of a repair's input) the mesh (V, F) holds
    (`mrepair inspect OUTPUT --reference INPUT`, its "reference" section), plus
    "lost": the int64 indices of the reference points neither within `tolerance`
    (None: 1e-6 x their bounding-box diagonal) of the surface nor inside it."""

DefectKind = Dict[str, Any]
"""one kind of defect: "count" (int) and int64 arrays "vertices", "edges" (k, 2),
"faces", "pairs" (k, 2) or "loops" (list of vertex arrays); see locate_defects"""

def locate_defects(
    V: Vertices,
    F: Faces,
    *,
    spike_angle: Optional[float] = None,
    small_hole: Optional[int] = None,
    small_component: Optional[int] = None,
    t_junction_tolerance: Optional[float] = None,
    self_intersections: bool = True,
    mesh: bool = False,
) -> Dict[str, DefectKind]:
    """where the defects that `inspect` counts are (doc/studio.md).

    Keys boundary_loops, small_holes, non_manifold_edges, non_manifold_vertices,
    spikes, near_degenerate_faces, small_components, crossing_pairs, t_junctions;
    each "count" equals the count of `inspect(V, F)` with the same options.
    Boundary loops are vertex walks (-1 ends each open walk of a loop that is not
    one closed walk); small_holes has "loops" and "indices" (into boundary_loops),
    small_components "faces" and "components", crossing_pairs "pairs", "touching"
    and "computed", t_junctions "vertices" and the "edges" they lie on.
    mesh=True inspects the faces as a polygon mesh (as mrepair.repair's "after"
    inspection: boundary loops are border cycles); ValueError if they are not one."""

def defect_overlay(
    V: Vertices,
    F: Faces,
    *,
    spike_angle: Optional[float] = None,
    small_hole: Optional[int] = None,
    small_component: Optional[int] = None,
    t_junction_tolerance: Optional[float] = None,
    self_intersections: bool = True,
    mesh: bool = False,
    max_elements: int = 100000,
) -> Dict[str, Dict[str, Dict[str, Any]]]:
    """the defects as geometry: {"kinds": {kind: {"count", "label", "color",
    "points" float32 (k, 3), "segments" (k, 6), "triangles" (k, 9), "first",
    "first_radius", "drawn", "truncated"}}}, at most max_elements elements per kind."""

def preview_mesh(
    V: Vertices, F: Faces, face_budget: int
) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32], bool]:
    """(V2, F2, decimated): the mesh as triangles when it has at most face_budget
    of them, else a vertex-clustering preview with at most face_budget triangles."""

def soup_to_manifold(
    V: Vertices,
    F: Faces,
    *,
    epsilon: float = 0.0,
    merge_epsilon: float = 0.0,
    keep_two_sided: bool = False,
    orient_outward: bool = True,
    progress: Progress = None,
) -> Result:
    """any polygon soup to a consistently oriented manifold triangle mesh (`mrepair soup`)."""

def close_gaps(
    V: Vertices,
    F: Faces,
    tolerance: Optional[float] = None,
    *,
    relative: bool = False,
    steps: Optional[int] = None,
    lambda_: float = 0.5,
    keep_pinched: bool = False,
    progress: Progress = None,
) -> Result:
    """closes cracks, gaps and T-junctions narrower than `tolerance` (`mrepair close-gaps`).

    tolerance=None raises ValueError: there is no automatic tolerance yet."""

def clean(
    V: Vertices,
    F: Faces,
    *,
    profile: str = "scan",
    only: Union[None, str, Iterable[str]] = None,
    skip: Union[None, str, Iterable[str]] = None,
    spike_angle: Optional[float] = None,
    max_hole: Optional[int] = None,
    min_component: Optional[int] = None,
    iterations: Optional[int] = None,
    boundary_angle: Optional[float] = None,
    density: Optional[float] = None,
    fair: bool = False,
    progress: Progress = None,
) -> Result:
    """the RameshCleaner pipeline on a manifold mesh (`mrepair clean`)."""

def repair(
    V: Vertices,
    F: Faces,
    *,
    profile: str = "auto",
    close_gaps: Optional[float] = None,
    merge_epsilon: Optional[float] = None,
    spike_angle: Optional[float] = None,
    max_hole: Optional[int] = None,
    min_component: Optional[int] = None,
    iterations: Optional[int] = None,
    self_intersections: bool = True,
    input_self_intersections: bool = False,
    resolve_intersections: bool = True,
    merge_overlapping_shells: bool = True,
    progress: Progress = None,
) -> Result:
    """the whole job of `mrepair repair`, keeping the user's model."""

def remesh(
    V: Vertices,
    F: Faces,
    *,
    edge_length: Optional[float] = None,
    tolerance: Optional[float] = None,
    faces: Optional[int] = None,
    feature_angle: Optional[float] = None,
    iterations: Optional[int] = None,
    min_edge_length: Optional[float] = None,
    max_edge_length: Optional[float] = None,
    protect_features: bool = False,
    progress: Progress = None,
) -> Result:
    """isotropic remeshing to edge_length, to about `faces` faces, or adaptive to `tolerance`."""

class GapClosingSequence:
    """the progressive gap closing as a sequence to step through (and back to the exact input)."""

    def __init__(
        self, V: Vertices, F: Faces, tolerance: float, *, relative: bool = False, lambda_: float = 0.5
    ) -> None: ...
    def forward(self, steps: int = 1) -> int:
        """applies up to `steps` contractions; returns how many."""
    def backward(self, steps: int = 1) -> int:
        """undoes up to `steps` contractions; returns how many."""
    def to_distance(self, distance: float) -> int:
        """moves to the given error level; returns contractions applied (> 0) or undone (< 0)."""
    def mesh(self) -> Tuple[npt.NDArray[np.float64], FacesOut]:
        """the mesh at the current position."""
    def report(self) -> Report:
        """the counters of the current position."""
    @property
    def position(self) -> int: ...
    @property
    def size(self) -> int: ...
    @property
    def current_distance(self) -> float: ...
    @property
    def max_distance(self) -> float: ...

def html_report(
    path: Union[str, PathLike[str]],
    V_before: Vertices,
    F_before: Faces,
    V_after: Vertices,
    F_after: Faces,
    report: Report,
    settings: Optional[Dict[str, Any]] = None,
    *,
    title: Optional[str] = None,
    face_budget: int = 500000,
    max_elements: int = 100000,
    spike_angle: Optional[float] = None,
    small_hole: Optional[int] = None,
    small_component: Optional[int] = None,
    t_junction_tolerance: Optional[float] = None,
    self_intersections: bool = True,
) -> None:
    """writes the self-contained HTML report (the page of `mrepair repair --html`): the before
    and after meshes with their defects in colour, the report tables and the settings.

    Needs the studio's built web assets (MREPAIR_STUDIO_ASSETS, the build folder, or
    <prefix>/share/mrepair/studio); FileNotFoundError says how to build them."""

def progress_bar(bar: Any) -> Callable[[str, float], None]:
    """a progress callable that drives a tqdm bar."""
