#!/usr/bin/env python3
"""NumPy reference for `qdot response --over` (benches/response.rs).

The chain of examples/damped_chain.qd: N equal masses m between two walls,
N + 1 springs k, a damper c from each mass to the ground, F0·cos(Ω·t) on
the first mass. The steady state X(Ω) = (K − Ω²M + iΩC)⁻¹·F at COUNT
frequencies from FROM to TO, solved by one batched complex LU
(numpy.linalg.solve on a stack of COUNT matrices).

    response_reference.py --time COUNT RUNS   best of RUNS, in seconds
    response_reference.py --check COUNT       |X| of every mass at COUNT
                                              frequencies, as JSON
"""
import json
import sys
import time

import numpy as np

N, M, K, C, F0 = 10, 1.0, 1.0, 0.02, 1.0
FROM, TO = 0.01, 2.5


def matrices():
    k = np.zeros((N, N))
    for i in range(N):
        k[i, i] = 2 * K
        if i + 1 < N:
            k[i, i + 1] = k[i + 1, i] = -K
    return M * np.eye(N), C * np.eye(N), k


def response(omega):
    m, c, k = matrices()
    w = omega[:, None, None]
    a = k[None] - w**2 * m[None] + 1j * w * c[None]
    f = np.zeros((len(omega), N, 1), dtype=complex)
    f[:, 0, 0] = F0
    return np.linalg.solve(a, f)[:, :, 0]


def main():
    if sys.argv[1:2] == ["--time"]:
        count, runs = int(sys.argv[2]), int(sys.argv[3])
        omega = np.linspace(FROM, TO, count)
        best = float("inf")
        for _ in range(runs):
            start = time.perf_counter()
            x = response(omega)
            np.abs(x), np.angle(np.conj(x))
            best = min(best, time.perf_counter() - start)
        print(best)
    elif sys.argv[1:2] == ["--check"]:
        omega = np.linspace(FROM, TO, int(sys.argv[2]))
        print(json.dumps(np.abs(response(omega)).tolist()))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
