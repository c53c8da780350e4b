"""Small dense linear programs, solved by HiGHS's dual simplex through its own Python interface
(highspy).

The fitter solves thousands of LPs of a few dozen columns and a few hundred rows; through
``scipy.optimize.linprog`` (the same solver, the same options) the per-call checks of the inputs
and of every option cost more than the solve. Here a problem goes to HiGHS as it is: minimise
``cost @ x`` subject to ``a_ub @ x <= b_ub`` and ``lower <= x <= upper`` (±inf: unbounded).
"""

from __future__ import annotations

import functools
import os
import sys

import numpy as np


@functools.cache
def _solver():
    """The process's HiGHS instance, set as linprog's ``method="highs-ds"`` sets it (quiet,
    presolve on, dual simplex), so the two give the same solutions. HiGHS prints a banner to
    standard output when its first instance is made: that is made with standard output shut."""
    import highspy

    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            highs = highspy.Highs()
    finally:
        os.dup2(saved, 1)
        os.close(saved)
    for name, value in (("output_flag", False), ("log_to_console", False), ("presolve", "on"),
                        ("solver", "simplex"), ("simplex_strategy", 1)):
        highs.setOptionValue(name, value)
    return highs


def solve_lp(cost: np.ndarray, a_ub: np.ndarray, b_ub: np.ndarray, lower: np.ndarray,
             upper: np.ndarray) -> np.ndarray | None:
    """The minimiser x of the LP above (HiGHS's optimal vertex), or None when HiGHS finds no
    optimum (infeasible, unbounded, or a numerical failure)."""
    import highspy

    a = np.asarray(a_ub, dtype=float)
    n_rows, n_cols = a.shape
    columns, rows = np.nonzero(a.T)  # column-wise nonzeros, rows ascending within a column
    lp = highspy.HighsLp()
    lp.num_col_, lp.num_row_ = n_cols, n_rows
    lp.col_cost_ = np.asarray(cost, dtype=float)
    lp.col_lower_ = np.asarray(lower, dtype=float)
    lp.col_upper_ = np.asarray(upper, dtype=float)
    lp.row_lower_ = np.full(n_rows, -np.inf)
    lp.row_upper_ = np.asarray(b_ub, dtype=float)
    lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
    lp.a_matrix_.num_col_, lp.a_matrix_.num_row_ = n_cols, n_rows
    lp.a_matrix_.start_ = np.concatenate(([0], np.cumsum(np.bincount(columns, minlength=n_cols)))).astype(np.int32)
    lp.a_matrix_.index_ = rows.astype(np.int32)
    lp.a_matrix_.value_ = a[rows, columns]
    highs = _solver()
    highs.clearModel()  # (and with it the previous solution and basis: every solve starts afresh)
    highs.passModel(lp)
    highs.run()
    if highs.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        return None
    return np.array(highs.getSolution().col_value)
