"""A second-order cone programme gathered block by block and solved with Clarabel: the form
each trust-region step of the 3-D fit takes (coatsim.geometry.space.tube)."""

from __future__ import annotations

import clarabel
import numpy as np
from scipy.sparse import coo_matrix, csc_matrix

SOLVER_TOL = 1e-7  # the cone solver's gap and feasibility tolerances


class ConeProgram:
    """A second-order cone programme  minimise cost·x  with  b − A x  in the cones (Clarabel),
    gathered block by block: linear rows (A x <= b) and blocks of 3-row cones (t, v) with
    |v| <= t, the linear ones first."""

    def __init__(self, width: int) -> None:
        self.width = width
        self.blocks: dict[bool, list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]] = {True: [], False: []}
        self.count = {True: 0, False: 0}

    def add(self, rows: np.ndarray, cols: np.ndarray, vals: np.ndarray, rhs: np.ndarray, cone: bool = False) -> None:
        """Rows numbered from 0 locally (entries with cols < 0, fixed unknowns, dropped);
        ``cone``: consecutive groups of 3 rows are second-order cones (the first the bound)."""
        rows, cols, vals = (np.asarray(x).ravel() for x in (rows, cols, vals))
        keep = cols >= 0
        rhs = np.asarray(rhs, dtype=float).ravel()
        linear = not cone
        self.blocks[linear].append((rows[keep] + self.count[linear], cols[keep], vals[keep].astype(float), rhs))
        self.count[linear] += len(rhs)

    def solve(self, cost: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> np.ndarray | None:
        """The minimiser within lower <= x <= upper (None if the solver fails)."""
        up, low = np.flatnonzero(np.isfinite(upper)), np.flatnonzero(np.isfinite(lower))
        box = len(up) + len(low)
        first = box + self.count[True]
        r, c, v, b = [np.arange(box), np.concatenate((up, low))], [], [], [upper[up], -lower[low]]
        c.append(r.pop())
        v.append(np.concatenate((np.ones(len(up)), -np.ones(len(low)))))
        for linear, offset in ((True, box), (False, first)):
            for rows, cols, vals, rhs in self.blocks[linear]:
                r.append(rows + offset), c.append(cols), v.append(vals), b.append(rhs)
        a = coo_matrix((np.concatenate(v), (np.concatenate(r), np.concatenate(c))),
                       shape=(first + self.count[False], self.width)).tocsc()
        cones = [clarabel.NonnegativeConeT(first)] + [clarabel.SecondOrderConeT(3)] * (self.count[False] // 3)
        settings = clarabel.DefaultSettings()
        settings.verbose = False
        settings.tol_gap_abs = settings.tol_gap_rel = settings.tol_feas = SOLVER_TOL
        solution = clarabel.DefaultSolver(csc_matrix((self.width, self.width)), cost, a, np.concatenate(b),
                                          cones, settings).solve()
        return np.array(solution.x) if str(solution.status) in ("Solved", "AlmostSolved") else None
