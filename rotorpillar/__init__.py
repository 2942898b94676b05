"""rotorpillar: dynamics of a heavy, eccentric rotor on a tall flexible pillar.

The library as a notebook uses it (the CLI, :mod:`rotorpillar.cli`, is a thin
layer over the same calls; ``examples/`` has short scripts)::

    from rotorpillar import load_scene, with_values, analyze
    scene = with_values(load_scene("paper"), {"shaft.stiffness": 5e6})
    result = analyze(scene)            # an AnalysisResult: result.system.omega, ...

Layers, bottom up (docs/architecture.md draws them):

- :mod:`rotorpillar.scene`, :mod:`.errors`, :mod:`.provenance`: the scene, the
  word lists, the errors, JSON records and atomic writes
- :mod:`rotorpillar.mesh`: Gmsh builders of the tube
- :mod:`rotorpillar.fem3d`: dolfinx elasticity, SLEPc modes, the Naghdi shell
- :mod:`rotorpillar.reduced`: closed forms, averaging, rotor-pillar ODEs (numpy/scipy/numba only)
- :mod:`rotorpillar.analysis`, :mod:`rotorpillar.converge`: the analyses and studies of a scene
- :mod:`rotorpillar.postprocess`: charts, renders, animations, the HTML report
- :mod:`rotorpillar.commands`, :mod:`rotorpillar.cli`: the command line

The names below are imported on first use, so ``import rotorpillar`` stays light.
"""

import importlib

__version__ = "0.1.0"

#: public name -> the module that defines it
_EXPORTS = {
    "Scene": "rotorpillar.scene",
    "load_scene": "rotorpillar.scene",
    "override": "rotorpillar.scene",
    "with_values": "rotorpillar.scene",
    "embedded_scenes": "rotorpillar.scene",
    "InputError": "rotorpillar.errors",
    "ComputationError": "rotorpillar.errors",
    "analyze": "rotorpillar.analysis",
    "AnalysisResult": "rotorpillar.analysis",
    "ModalSummary": "rotorpillar.fem3d.modal_summary",
    "modal_analysis": "rotorpillar.fem3d",
    "run_case": "rotorpillar.transients.cases",
    "CaseSummary": "rotorpillar.transients.case_summary",
    "ConvergenceStudy": "rotorpillar.converge.result",
    "CompareResult": "rotorpillar.transients.compare",
    "compare_models": "rotorpillar.transients.compare",
    "StudyResult": "rotorpillar.studies.result",
    "design_study": "rotorpillar.studies.study",
}

__all__ = sorted(_EXPORTS) + ["__version__"]


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rotorpillar' has no attribute {name!r}")


def __dir__():
    return __all__
