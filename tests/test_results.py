"""The typed results that cross a layer round-trip through their JSON exactly.

Reference: the JSON the commands write (analyze.json, modal.json); a record
read back from it must give the same dict, key for key and value for value
(``from_json(d).to_json() == d``), so the report reading through the records
sees what the command computed.
"""

import json

import pytest

from rotorpillar import analyze, load_scene, override
from rotorpillar.analysis import AnalysisResult
from rotorpillar.provenance import to_json


@pytest.mark.parametrize("overrides", [[], ["shaft.stiffness=5e6"], ["rotor.eccentricity=0.04"]])
def test_analysis_round_trips_through_its_json(overrides):
    result = analyze(override(load_scene("paper"), overrides))
    doc = json.loads(to_json(result))  # as analyze.json holds it
    back = AnalysisResult.from_json(doc)
    assert back.to_json() == doc
    assert back.system.omega == pytest.approx(result.system.omega)
    assert back.resonances[0].curves.a == pytest.approx(list(result.resonances[0].curves.a))


def test_a_missing_field_names_itself():
    doc = json.loads(to_json(analyze(load_scene("paper"))))
    del doc["drive"]
    with pytest.raises(KeyError, match="drive"):
        AnalysisResult.from_json(doc)


def test_modal_summary_round_trips(tmp_path):
    pytest.importorskip("dolfinx")
    from rotorpillar.fem3d import modal_analysis
    from rotorpillar.fem3d.modal_summary import ModalComparison, ModalMesh, ModalSummary, modal_summary
    from rotorpillar.reduced.reduction import pillar_closed_forms

    scene = load_scene("paper", ["mesh.elements_around=8", "mesh.elements_along=4", "modal.n_modes=4"])
    summary = modal_summary(
        scene, modal_analysis(scene, top=False), modal_analysis(scene, top=True), pillar_closed_forms(scene.pillar)
    )
    doc = json.loads(to_json(summary))
    back = ModalSummary.from_json(doc)
    assert back.to_json() == doc
    # the typed sections come back as records, their leaves as the scene set them
    assert isinstance(back.mesh, ModalMesh) and isinstance(back.comparison, ModalComparison)
    assert (back.mesh.elements_around, back.mesh.elements_along) == (8, 4)
    assert back.modes == summary.modes and back.reduction == summary.reduction
    assert back.configurations.with_top.dofs == summary.mesh.dofs_with_top
    assert doc["reduction"]["m_reduced"] > 0
