"""Mode shapes to disk: one VTU per configuration, for ParaView, pyvista, meshio.

The tube's first-order cells at its vertices, one point array per mode,
``mode_000``, ``mode_001``, ... (3-vector displacement, the normalised shape
of modal.json's list in the same order; the frequencies are in modal.json).
Written atomically on rank 0 only.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..provenance import atomic_path

VTK_CELL = {"hexahedron": "hexahedron", "tetrahedron": "tetra"}


def mode_array_name(i: int) -> str:
    """Point-array name of mode i: mode_000, mode_001, ..."""
    return f"mode_{i:03d}"


def write_modes_vtu(path: str | Path, result) -> Path:
    """Write a ModalResult's shapes to ``path`` (.vtu); call on rank 0."""
    import meshio
    if result.shapes is None:
        raise ValueError("this ModalResult has no shapes (not rank 0?)")
    point_data = {mode_array_name(i): np.ascontiguousarray(result.shapes[i], dtype=np.float64)
                  for i in range(len(result.omega))}
    mesh = meshio.Mesh(np.asarray(result.points, dtype=np.float64),
                       [(VTK_CELL[result.cell_type], np.asarray(result.vtu_cells, dtype=np.int64))],
                       point_data=point_data)
    with atomic_path(path) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
    return Path(path)
