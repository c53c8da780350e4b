"""Part meshes: read a triangle mesh file, bring it to millimetres, repair what can be repaired.

``load_part`` reads STL (ASCII or binary), PLY, OBJ, OFF and GLB/glTF through trimesh. It merges
duplicate vertices (an STL stores every corner of every triangle), drops degenerate and duplicate
triangles and unreferenced vertices, and says so in the part's notes. What cannot be repaired
(no triangles, coordinates that are not numbers, a mesh with no extent, a file over the budget)
is refused with one line naming the problem and the fix.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coatsim.core import defaults
from coatsim.core.budgets import MAX_ABS_COORDINATE_MM, check_budget
from coatsim.core.errors import InputError
from coatsim.core.fileio import read_input
from coatsim.core.units import UNITS_MM

#: millimetres per unit of a mesh file
UNIT_CHOICES = (*UNITS_MM, "auto")
#: ``units="auto"``: a part whose largest extent is below this many file units is read as metres
#: (a part an arm sprays is rarely larger than 2.5 m) ...
AUTO_METRES_BELOW = 2.5
#: ... and from there to this many as inches (64–254 mm: as many metres fit no arm's reach, and as
#: many millimetres are rarely a sprayed part; CAD exports without units are often in inches)
AUTO_INCHES_BELOW = 10.0
#: units trimesh reports for files that carry them (glTF is metres by its specification)
_TRIMESH_UNITS = {"millimeters": "mm", "millimeter": "mm", "mm": "mm", "centimeters": "cm", "cm": "cm",
                  "meters": "m", "meter": "m", "m": "m", "inches": "in", "inch": "in", "in": "in"}
MESH_SUFFIXES = (".stl", ".ply", ".obj", ".off", ".glb", ".gltf")
#: vertices closer than this fraction of the part's extent are one vertex
MERGE_FRACTION = 1e-9
#: triangles thinner than this fraction of the extent (height over their longest edge) are degenerate:
#: a zero-area triangle, or a sliver along an edge rounded off its line (both left by exporters)
SLIVER_FRACTION = 1e-7


@dataclass(frozen=True, eq=False)
class Part:
    """A part mesh in millimetres in its own frame: vertices (n, 3), triangles (m, 3) int64,
    the file it came from with its SHA-256, the unit it was read in, and what reading found;
    ``units_guess`` says how the unit was guessed from the extent ("" when given or in the file)."""

    file: str
    sha256: str
    vertices_mm: np.ndarray
    faces: np.ndarray
    units: str
    notes: tuple[str, ...]
    units_guess: str = ""

    @property
    def extent_mm(self) -> float:
        return float(np.ptp(self.vertices_mm, axis=0).max())


def load_part(path: str | Path, units: str = defaults.PLAN_UNITS) -> Part:
    """Read a mesh file (see the module docstring), repaired and checked.

    Args:
        path: an STL (ASCII or binary), PLY, OBJ, OFF, GLB or glTF file.
        units: the file's length unit: mm, cm, m, in, or auto (from the extent, with a note).

    Returns:
        The Part: its mesh in mm, with the notes of what was repaired.

    Raises:
        InputError: a file that is not a mesh, or a mesh that cannot be repaired (one line
            naming the problem and the fix).
        BudgetExceeded: more triangles or bytes than the plan budgets.
    """
    import trimesh

    path = Path(path)
    if units not in UNIT_CHOICES:
        raise InputError(f"units must be one of {', '.join(UNIT_CHOICES)}, found {units!r}", parameters=("units",))
    if path.suffix.lower() not in MESH_SUFFIXES:
        raise InputError(f"{path}: not a mesh file this reader knows (suffix {path.suffix or 'none'}); "
                         f"export the part as {', '.join(s[1:].upper() for s in MESH_SUFFIXES)}")
    data = read_input(path, "part mesh", "plan_mesh_bytes")
    if path.suffix.lower() == ".stl":
        _check_stl(path, data)
    try:
        mesh = trimesh.load(str(path), force="mesh", process=False)
    except Exception as exc:  # trimesh raises many types for malformed files
        first = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
        raise InputError(f"{path}: cannot read the mesh ({first}); check that the file is a complete "
                         f"{path.suffix[1:].upper()} export") from None
    faces = np.asarray(getattr(mesh, "faces", np.zeros((0, 3))), dtype=np.int64).reshape(-1, 3)
    if len(faces) == 0:
        raise InputError(f"{path}: the file holds no triangles (a point cloud or an empty export); "
                         "mesh the scan first (e.g. Poisson reconstruction) and export the surface")
    check_budget(f"{path}: triangles", len(faces), "plan_triangles",
                 "decimate the mesh (e.g. MeshLab quadric edge collapse)")
    file_units = units_of(mesh)
    vertices = np.asarray(mesh.vertices, dtype=float)
    return _part(str(path), hashlib.sha256(data).hexdigest(), vertices, faces, units, file_units)


def _check_stl(path: Path, data: bytes) -> None:
    """A binary STL states its triangle count: refuse a truncated file, and one over the budget
    before it is read. An ASCII one (it starts with 'solid' and is not binary-sized) closes every
    facet it opens and ends with 'endsolid': refuse one cut off (its reader keeps nothing of it)."""
    if data[:5].lower() == b"solid" and (len(data) < 84 or (len(data) - 84) % 50 != 0):
        text = data.lower()
        opened, closed = text.count(b"facet normal"), text.count(b"endfacet")
        if opened != closed or b"endsolid" not in text[-4096:]:
            raise InputError(f"{path}: the ASCII STL is cut off ({opened} facets begun, {closed} ended"
                             f"{'' if b'endsolid' in text[-4096:] else ', no endsolid'}); the file is truncated or "
                             "damaged, export it again")
        return
    if len(data) < 84:
        return
    count = int.from_bytes(data[80:84], "little")
    if len(data) != 84 + 50 * count:
        raise InputError(f"{path}: a binary STL of {count} triangles should be {84 + 50 * count} bytes, the file has "
                         f"{len(data)}; the file is truncated or damaged, export it again")
    check_budget(f"{path}: triangles", count, "plan_triangles",
                 "decimate the mesh (e.g. MeshLab quadric edge collapse)")


def part_from_arrays(vertices: np.ndarray, faces: np.ndarray, name: str = "mesh", units: str = "mm") -> Part:
    """A part from vertex (n, 3) and triangle (m, 3) arrays, repaired as a file would be."""
    vertices = np.ascontiguousarray(vertices, dtype=float).reshape(-1, 3)
    faces = np.ascontiguousarray(faces, dtype=np.int64).reshape(-1, 3)
    if units not in UNIT_CHOICES:
        raise InputError(f"units must be one of {', '.join(UNIT_CHOICES)}, found {units!r}", parameters=("units",))
    if len(faces) == 0:
        raise InputError(f"{name}: the mesh holds no triangles")
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise InputError(f"{name}: a triangle refers to a vertex that does not exist")
    check_budget(f"{name}: triangles", len(faces), "plan_triangles", "decimate the mesh")
    digest = hashlib.sha256(vertices.tobytes() + faces.tobytes()).hexdigest()
    return _part(name, digest, vertices, faces, units, None)


def _part(name: str, digest: str, vertices: np.ndarray, faces: np.ndarray, units: str,
          file_units: str | None) -> Part:
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise InputError(f"{name}: a triangle refers to a vertex that does not exist; re-export the mesh")
    used = np.unique(faces)
    if not np.all(np.isfinite(vertices[used])):
        raise InputError(f"{name}: vertex coordinates that are not numbers (nan or inf); re-export the mesh")
    extent = float(np.ptp(vertices[used], axis=0).max())
    if not extent > 0:
        raise InputError(f"{name}: every vertex is at one point (the mesh has no extent)")
    unit, guess = length_unit(extent, units, file_units)
    notes = [guessed_unit_note(unit, guess)] if guess else []
    notes += [f"units auto: the file says {file_units}"] if units == "auto" and file_units is not None else []
    far = float(np.abs(vertices[used]).max()) * UNITS_MM[unit]
    if not far <= MAX_ABS_COORDINATE_MM:
        raise InputError(f"{name}: a vertex {far:.3g} mm from the origin, beyond {MAX_ABS_COORDINATE_MM:g} mm; "
                         "re-export the mesh")
    vertices, faces = _repaired(vertices * UNITS_MM[unit], faces, name, notes)
    return Part(name, digest, vertices, faces, unit, tuple(notes), guess)


def units_of(mesh: object) -> str | None:
    """The unit a mesh loaded by trimesh says its file is in (None where it says none)."""
    return _TRIMESH_UNITS.get(str(getattr(mesh, "units", None) or "").lower())


def guessed_unit_note(unit: str, guess: str) -> str:
    """What the user is told where the unit was guessed from the extent (``length_unit``)."""
    others = {"m": "mm, cm or inches", "in": "mm, cm or m"}.get(unit, "m, cm or inches")
    return f"units auto: {guess}; give the units if the file is in {others}"


def length_unit(extent: float, units: str, file_units: str | None) -> tuple[str, str]:
    """The unit the file is read in, and how it was guessed from the extent ("" when given or in the file)."""
    if units != "auto":
        return units, ""
    if file_units is not None:
        return file_units, ""
    if extent < AUTO_METRES_BELOW:
        return "m", f"largest extent {extent:.4g} read as metres ({extent * 1000:.4g} mm)"
    if extent < AUTO_INCHES_BELOW:
        return "in", f"largest extent {extent:.4g} read as inches ({extent * UNITS_MM['in']:.4g} mm)"
    return "mm", f"largest extent {extent:.4g} read as millimetres"


def _repaired(vertices: np.ndarray, faces: np.ndarray, name: str, notes: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """Merge duplicate vertices, drop degenerate and duplicate triangles and unused vertices."""
    used = np.unique(faces)
    extent = float(np.ptp(vertices[used], axis=0).max())
    key = np.round((vertices - vertices[used].min(axis=0)) / (MERGE_FRACTION * extent)).astype(np.int64)
    _, first, merged = np.unique(key, axis=0, return_index=True, return_inverse=True)
    merged = merged.ravel()
    merged_count = len(used) - len(np.unique(merged[used]))
    faces = merged[faces]
    vertices = vertices[first]
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    longest = np.linalg.norm(np.stack((b - a, c - b, a - c)), axis=2).max(axis=0)
    good = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 2] != faces[:, 0])
    good &= area2 > SLIVER_FRACTION * extent * longest  # height = area2 / longest
    if not good.any():
        raise InputError(f"{name}: every triangle is degenerate (zero area); re-export the surface")
    if (~good).sum():
        notes.append(f"dropped {int((~good).sum())} degenerate triangle(s) (zero area, or thinner than "
                     f"{SLIVER_FRACTION * extent:.2g} mm)")
    faces = faces[good]
    _, unique = np.unique(np.sort(faces, axis=1), axis=0, return_index=True)
    if len(unique) < len(faces):
        notes.append(f"dropped {len(faces) - len(unique)} duplicate triangle(s)")
    faces = faces[np.sort(unique)]
    if merged_count:
        notes.append(f"merged {merged_count} duplicate vertices")
    used, local = np.unique(faces, return_inverse=True)
    return vertices[used], local.reshape(-1, 3).astype(np.int64)

