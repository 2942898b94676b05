"""rotorpillar: dynamics of a heavy, eccentric rotor on a tall flexible pillar.

Library layout (a thin CLI sits on top, see :mod:`rotorpillar.cli`):

- :mod:`rotorpillar.scene`     the scene: TOML in, validated frozen dataclasses
- :mod:`rotorpillar.reduced`   closed forms, averaging, rotor-pillar ODEs (numpy/scipy only)
- :mod:`rotorpillar.mesh`      Gmsh builders of the tube
- :mod:`rotorpillar.fem3d`     dolfinx elasticity and SLEPc modes of the tube
- :mod:`rotorpillar.postprocess` charts, renders, animations, the HTML report
"""

__version__ = "0.1.0"
