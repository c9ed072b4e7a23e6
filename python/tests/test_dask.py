"""The Dask example (examples/dask_sweep.py) on a LocalCluster: the rows the
workers compute are the rows computed here."""

import importlib.util
import pickle

import numpy as np
import pytest

import qdot
from conftest import ROOT

distributed = pytest.importorskip("dask.distributed")


def load_example():
    spec = importlib.util.spec_from_file_location("dask_sweep", ROOT / "examples" / "dask_sweep.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_scene_pickles_as_its_text():
    scene = qdot.Scene.load(ROOT / "examples" / "double_pendulum.qd")
    data = pickle.dumps(scene)
    assert len(data) < 2 * len(scene.source.encode()) + 200
    again = pickle.loads(data)
    assert again.accelerations() == scene.accelerations()


def test_dask_local_cluster_sweep():
    example = load_example()
    scene = qdot.Scene.load(example.SCENE)
    theta1s = np.linspace(-2, 2, 4)
    theta2_range = (-2, 2, 5)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        got = example.chart(client, scene, theta1s, theta2_range, t_end=2)
    want = np.array([example.chart_row(scene, th1, theta2_range, 2) for th1 in theta1s])
    assert got.shape == (4, 5)
    assert np.array_equal(got, want)
