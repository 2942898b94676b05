"""Charts, renders and reports: the only place that imports matplotlib or pyvista (lazily)."""
