"""The robust study on Dask with the study store: the same probabilities as in process, and
a rerun resumes from the SQLite store without computing a state again."""

from __future__ import annotations

import pytest

import chaindrive
from chaindrive.robust import (
    UncertaintySettings,
    nominal_analysis,
    reliability,
    uncertainty_model,
)
from chaindrive.robust.study import DaskOptions, dask_states
from chaindrive.synthesis.studies import StudyStore
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.concurrency  # Dask clusters

distributed = pytest.importorskip("distributed")


def test_dask_states_match_serial_and_resume(tmp_path) -> None:
    nominal = nominal_analysis(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"))
    model = uncertainty_model(nominal, UncertaintySettings(samples=8, replicates=2, seed=2))
    serial = reliability(nominal, model)
    url = f"sqlite:///{tmp_path / 'robust.db'}"
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        options = DaskOptions(db=url, study="robust", client=client, progress=False)
        first = reliability(nominal, model, evaluator=dask_states(options))
        stored = StudyStore(url).count("robust")
        again = reliability(nominal, model, evaluator=dask_states(options))
    assert stored == 8
    assert StudyStore(url).count("robust") == stored      # the rerun computed nothing new
    for result in (first, again):
        assert [(c.key, c.failures) for c in result.checks] == [
            (c.key, c.failures) for c in serial.checks]
        assert result.quantile("f1_hz", 0.5) == pytest.approx(serial.quantile("f1_hz", 0.5),
                                                              rel=1e-9)
