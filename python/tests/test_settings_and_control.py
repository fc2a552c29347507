# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Settings by registry name (the same maps as comap match --settings), threads, the progress
callback, and stopping a run: by the callback and by Ctrl-C."""

import json
import os
import signal
import subprocess

import numpy as np
import pytest

import comap
from test_match import pair, result, write_off  # noqa: F401 (fixtures)

EXPERT = {"number_of_candidates": 12, "ring_schedule": [2, 1], "use_coupled_zoomout": False,
          "refinement_selection": "refined", "initialization_fits": [[20, 0.03, 0.3], [30, 0.1, 1.0]]}


def test_settings_give_the_maps_of_the_command_line(tmp_path, pair, result):
    V1, F1, V2, F2 = pair
    m12, m21, info = comap.match(*pair, settings=EXPERT)
    assert not (np.array_equal(m12, result[0]) and np.array_equal(m21, result[1]))  # the settings were used
    write_off(tmp_path / "a.off", V1, F1)
    write_off(tmp_path / "b.off", V2, F2)
    (tmp_path / "expert.json").write_text(json.dumps(EXPERT))
    subprocess.run([os.environ.get("COMAP", "comap"), "match", str(tmp_path / "a.off"), str(tmp_path / "b.off"),
                    "--out-12", str(tmp_path / "12.txt"), "--out-21", str(tmp_path / "21.txt"), "--index-base", "0",
                    "--settings", str(tmp_path / "expert.json"), "--quiet"], check=True, timeout=600)
    assert np.array_equal(np.loadtxt(tmp_path / "12.txt", dtype=np.int64), m12)
    assert np.array_equal(np.loadtxt(tmp_path / "21.txt", dtype=np.int64), m21)
    # Without the refinement the maps are those that entered it.
    u12, u21, info = comap.match(*pair, settings={"use_refinement": False})
    assert not info["refined"]
    assert np.array_equal(u12, info["unrefined_map_12"]) and np.array_equal(u21, info["unrefined_map_21"])


def test_settings_registry():
    registry = comap.settings()
    assert registry["number_of_candidates"]["stage"] == "refinement"
    assert registry["number_of_eigenpairs"] == {
        "type": "int", "default": "100", "default_for_given_maps": "100", "range": "[2, 100000]",
        "stage": "preparation",
        "documentation": "Laplace-Beltrami eigenpairs of the refinement's descriptor stack (HKS, WKS)"}
    assert len(registry) > 50


@pytest.mark.parametrize("settings, words", [
    ({"number_of_candidate": 5}, ['unknown setting "number_of_candidate"', 'did you mean "number_of_candidates"']),
    ({"number_of_candidates": 0}, ["number_of_candidates = 0", "out of its range"]),
    ({"use_refinement": "yes"}, ["use_refinement must be true or false"]),
    ({"number_of_candidates": 2.5}, ["number_of_candidates must be an integer"]),
    ({"refinement_selection": "best"}, ["refinement_selection must be"]),
    ({"ring_schedule": [2, "x"]}, ["ring_schedule", "not a number"]),
    ([("number_of_candidates", 5)], ["settings must be a dict"]),
])
def test_bad_settings_raise_value_errors(pair, settings, words):
    with pytest.raises(ValueError) as e:
        comap.match(*pair, settings=settings)
    for w in words:
        assert w in str(e.value), str(e.value)


def test_preparation_settings_belong_to_shapes(pair, result):
    V1, F1, V2, F2 = pair
    s1, s2 = comap.Shape(V1, F1, threads=1), comap.Shape(V2, F2)
    with pytest.raises(ValueError, match="number_of_eigenpairs is a setting of the shapes' preparation"):
        comap.match_shapes(s1, s2, settings={"number_of_eigenpairs": 50})
    # Prepared with other preparation settings, the shapes give the maps of match with them.
    prep = {"number_of_eigenpairs": 50, "hks_weight": 1.0}
    a = comap.match_shapes(comap.Shape(V1, F1, settings=prep), comap.Shape(V2, F2, settings=prep),
                           settings={"number_of_candidates": 12})
    b = comap.match(*pair, settings=dict(prep, number_of_candidates=12))
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


def test_threads(pair, result):
    m12, m21, _ = comap.match(*pair, threads=1)
    assert np.array_equal(m12, result[0]) and np.array_equal(m21, result[1])
    for bad in (0, -2, 1.5, True):
        with pytest.raises(ValueError, match="threads must be a positive integer"):
            comap.match(*pair, threads=bad)


def test_progress_callback_sees_every_stage(pair, result):
    events = []
    m12, m21, _ = comap.match(*pair, progress=lambda stage, fraction: events.append((stage, fraction)))
    assert np.array_equal(m12, result[0]) and np.array_equal(m21, result[1])
    stages = [s for s, _ in events]
    for s in ("validation", "preparation", "initialization", "refinement", "selection"):
        assert (s, 0.0) in events and (s, 1.0) in events, s
    assert stages.index("preparation") < stages.index("initialization") < stages.index("refinement")
    assert all(0.0 <= f <= 1.0 for _, f in events)
    assert any(s == "initialization" and 0 < f < 1 for s, f in events)


def test_callback_stops_the_run(pair):
    seen = []

    def stop_at_refinement(stage, fraction):
        seen.append(stage)
        return stage != "refinement"

    with pytest.raises(comap.Stopped, match="stopped by the visitor during the refinement stage"):
        comap.match(*pair, progress=stop_at_refinement)
    assert seen[-1] == "refinement" and "selection" not in seen
    assert issubclass(comap.Stopped, RuntimeError)

    def fails(stage, fraction):
        if stage == "initialization":
            raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        comap.match(*pair, progress=fails)
    with pytest.raises(ValueError, match="progress must be a callable"):
        comap.match(*pair, progress=3)


def test_ctrl_c_stops_the_run(pair):
    # The callback presses Ctrl-C (SIGINT to the process) as the initialisation begins; the run
    # stops at its next event and raises KeyboardInterrupt, before the selection stage.
    seen = []

    def press_ctrl_c(stage, fraction):
        seen.append(stage)
        if stage == "initialization" and fraction == 0.0:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        comap.match(*pair, progress=press_ctrl_c)
    assert "initialization" in seen and "selection" not in seen
    # The module still works afterwards.
    m12, _, _ = comap.match(*pair, settings={"use_refinement": False})
    assert len(m12) == len(pair[0])


def test_settings_files_are_read_by_the_library(tmp_path):
    (tmp_path / "expert.json").write_text(
        '// expert run\n{\n  "number_of_candidates": 60, // more\n  "ring_schedule": [3, 2, 1],\n'
        '  "use_coupling": false,\n  "unary_weight": null,\n  "initialization_fits": [[20, 0.03, 0.3]]\n}\n')
    assert comap.read_settings(tmp_path / "expert.json") == {
        "number_of_candidates": 60.0, "ring_schedule": [3.0, 2.0, 1.0], "use_coupling": False,
        "initialization_fits": [[20.0, 0.03, 0.3]]}
    # What `comap settings` prints reads back: every setting whose default does not depend on the
    # maps' origin, at its default.
    template = subprocess.run([os.environ.get("COMAP", "comap"), "settings"], check=True, capture_output=True,
                              text=True, timeout=60).stdout
    (tmp_path / "all.json").write_text(template)
    read = comap.read_settings(tmp_path / "all.json")
    registry = comap.settings()
    assert set(read) == {n for n, s in registry.items() if s["default"] == s["default_for_given_maps"]}
    assert read["number_of_eigenpairs"] == float(registry["number_of_eigenpairs"]["default"])
    (tmp_path / "typo.json").write_text('{\n  "number_of_candidate": 5\n}\n')
    with pytest.raises(ValueError, match=r'typo.json:2: .*did you mean "number_of_candidates"'):
        comap.read_settings(tmp_path / "typo.json")
    (tmp_path / "broken.json").write_text('{\n  "ring_schedule": [3,, 1]\n}\n')
    with pytest.raises(OSError, match=r"broken.json:2:\d+: expected a number"):
        comap.read_settings(tmp_path / "broken.json")
    with pytest.raises(OSError, match="missing.json"):
        comap.read_settings(tmp_path / "missing.json")
