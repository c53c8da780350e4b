"""Paths on 3-D parts: passes planned on a triangle mesh (raster, geodesic, boundary).

``load_part`` reads a mesh file, ``plan`` turns it and ``PlanOptions`` into ``SurfacePaths``
(points on the surface, outward normals, spraying order), ``write_surfacepaths`` and
``read_surfacepaths`` handle the ``coatsim.surfacepaths/1`` file. Modules:

- mesh: reading, units, repair; topology: edges, borders, pieces; normals: orientation, smoothing
- region: which faces are coated; piece: a connected piece of the region
- raster, geodesic, boundary: the patterns; distance: heat method and fast marching;
  contours: level sets
- passes: edge band, spraying order, leads; spacing: ripple and measured gaps
- surfacepaths: the result and its file; verify: the independent check; planner: the pipeline
"""

from coatsim.geometry.surface.geodesic import FromBoundary, FromPlane, FromPoints
from coatsim.geometry.surface.mesh import Part, load_part, part_from_arrays
from coatsim.geometry.surface.planner import PlanOptions, plan
from coatsim.geometry.surface.region import Box, Everything, Facing
from coatsim.geometry.surface.surfacepaths import Pass, SurfacePaths, read_surfacepaths, write_surfacepaths

__all__ = ["Box", "Everything", "Facing", "FromBoundary", "FromPlane", "FromPoints", "Part", "Pass", "PlanOptions",
           "SurfacePaths", "load_part", "part_from_arrays", "plan", "read_surfacepaths", "write_surfacepaths"]
