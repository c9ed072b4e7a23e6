"""A stability chart of the double pendulum on a Dask cluster.

Which starting angles (θ₁, θ₂), released from rest, make the lower rod flip
over (|θ₂| > π) within t_end? Each Dask task is one row of the chart: one
θ₁, every θ₂, run by qdot's own sweep on one thread. The scene travels to
the workers as its text (a qdot.Scene pickles so) and is derived there once
per task, in about a millisecond.

    python examples/dask_sweep.py                 # on a LocalCluster, 1 then 2 workers
    python examples/dask_sweep.py tcp://host:8786 # on a running cluster

On a real cluster the same code runs unchanged: only the Client differs.
"""

import sys
import time
from pathlib import Path

import numpy as np

import qdot

SCENE = Path(__file__).with_name("double_pendulum.qd")
VALUES = {"m1": 1, "m2": 1, "l1": 1, "l2": 1, "g": 9.81}


def chart_row(scene, theta1, theta2_range, t_end):
    """One row: θ₁ fixed, θ₂ over (from, to, count); max |θ₂| of each run."""
    sweep = scene.sweep(
        set=VALUES,
        init={"th1": theta1, "th1'": 0, "th2'": 0},
        vary={"th2": theta2_range},
        t_end=t_end,
        threads=1,
    )
    return sweep.max_abs_q[:, 1]


def chart(client, scene, theta1s, theta2_range, t_end):
    """The chart, rows in θ₁ order: (len(theta1s), count) of max |θ₂|."""
    futures = client.map(
        chart_row,
        [scene] * len(theta1s),
        list(theta1s),
        [theta2_range] * len(theta1s),
        [t_end] * len(theta1s),
        pure=False,
    )
    return np.array(client.gather(futures))


def main(address=None):
    from dask.distributed import Client, LocalCluster

    scene = qdot.Scene.load(SCENE)
    theta1s = np.linspace(-3, 3, 40)
    theta2_range = (-3, 3, 40)
    runs = len(theta1s) * theta2_range[2]
    if address:
        with Client(address) as client:
            start = time.perf_counter()
            flips = chart(client, scene, theta1s, theta2_range, t_end=10) > np.pi
            seconds = time.perf_counter() - start
            print(f"{runs} runs in {seconds:.2f} s: {runs / seconds:.0f} simulations/s")
            print(f"{flips.mean():.0%} of the starts flip within t = 10")
        return
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            chart(client, scene, theta1s[:2], theta2_range, t_end=1)  # warm the workers
            start = time.perf_counter()
            flips = chart(client, scene, theta1s, theta2_range, t_end=10) > np.pi
            seconds = time.perf_counter() - start
            print(f"{workers} worker(s): {runs} runs in {seconds:.2f} s, {runs / seconds:.0f} simulations/s;"
                  f" {flips.mean():.0%} flip within t = 10")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
