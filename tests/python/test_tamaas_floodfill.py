"""Junction labelling (`wearsim junctions`) against tamaas's periodic FloodFill on random maps."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

tm = pytest.importorskip("tamaas", reason="tamaas not installed: pip install tamaas")
from tamaas_helpers import same_partition, tamaas_labels  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
WEARSIM = os.environ.get("WEARSIM_BIN", str(ROOT / "target" / "release" / "wearsim"))


@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("seed", range(6))
def test_labels_match_tamaas_floodfill(tmp_path, connectivity, seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(8, 48))
    contact = rng.random((n, n)) < rng.uniform(0.2, 0.6)
    np.save(tmp_path / "map.npy", contact)
    out = tmp_path / "out"
    subprocess.run(
        [WEARSIM, "junctions", str(tmp_path / "map.npy"), "--connectivity", str(connectivity), "--out", str(out)],
        check=True,
        capture_output=True,
    )
    labels = np.load(out / "labels.npy")
    info = json.loads((out / "junctions.json").read_text())
    expected = tamaas_labels(contact, connectivity == 8)
    assert info["junctions"] == expected.max() + 1
    assert same_partition(labels, expected)
    assert sorted(info["pixels"]) == sorted(np.bincount(expected[expected >= 0]).tolist())
