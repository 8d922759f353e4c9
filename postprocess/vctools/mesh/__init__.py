"""Mesh generation for vemcontact: Voronoi bodies with joints, structured meshes, Gmsh import.

Entry points: ``python -m vctools.mesh --help`` (or the ``vc-mesh`` console script).
"""
from .errors import MeshError
from .mesh import Mesh
from .scene import build, mesh_scene_file
from .deck import write_deck
from .quality import quality, report_lines

__all__ = ["MeshError", "Mesh", "build", "mesh_scene_file", "write_deck", "quality", "report_lines"]
