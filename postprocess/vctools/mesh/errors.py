"""The one exception type of the mesher: a clear message, never a broken mesh."""


class MeshError(ValueError):
    """Degenerate input or a mesh that cannot honour the geometry."""
