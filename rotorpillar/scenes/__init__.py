"""Embedded scenes: TOML files shipped with the package (see rotorpillar.scene)."""
