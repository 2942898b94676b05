"""Gmsh geometry builders: each ``(model, params) -> tags`` adds named physical groups."""
