"""Finite-element models of the pillar in dolfinx (the 3D solid and the shell)."""
