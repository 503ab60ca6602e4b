"""Natural modes of n coordinates worked out with numbers: frequencies, damping ratios and
shapes of hand-written mass, stiffness and damping matrices, and the modes that do not exist
(an unstable equilibrium, a free mode, a coordinate that does not move)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from mechgrade.mechanics.vibration import Modal, NaturalMode, modal_entries, modal_value


def _entries(M, K, C, residual=None):
    """The balances M q'' = -K q - C q' + residual at rest, as :func:`modal_entries` lays
    them out (no reactions: A = M)."""
    n = len(M)
    zero = np.zeros((n, n))
    b = np.zeros(n) if residual is None else np.asarray(residual, float)
    return modal_entries(M, b, [zero] * n, [-np.asarray(K, float)[:, j] for j in range(n)],
                         [zero] * n, [-np.asarray(C, float)[:, j] for j in range(n)])


M3 = np.diag([3.0, 2.0, 1.0])
K3 = np.array([[700.0, -300.0, 0.0], [-300.0, 500.0, -200.0], [0.0, -200.0, 200.0]])


def _value(what, number, entries, i=0, j=0):
    n = next(n for n in range(1, 9) if (2 * n + 1) * (n * n + n) == len(entries))
    return float(modal_value(what, number, i, j, n, n, *entries))


def test_the_frequencies_of_a_chain_are_the_generalised_eigenvalues():
    entries = _entries(M3, K3, np.zeros((3, 3)))
    root = np.diag(1 / np.sqrt(np.diag(M3)))
    expected = np.sqrt(np.linalg.eigvalsh(root @ K3 @ root))
    got = [_value(Modal.FREQUENCY, r, entries) for r in (1, 2, 3)]
    assert got == pytest.approx(expected, rel=1e-12)


def test_proportional_damping_gives_each_mode_half_its_frequency_times_beta():
    beta = 0.004  # C = beta K: zeta_r = beta w_r / 2 for every mode
    entries = _entries(M3, K3, beta * K3)
    for r in (1, 2, 3):
        w = _value(Modal.FREQUENCY, r, entries)
        assert _value(Modal.DAMPING_RATIO, r, entries) == pytest.approx(beta * w / 2,
                                                                        rel=1e-10)


def test_a_mode_shape_is_the_eigenvector_ratio():
    entries = _entries(M3, K3, np.zeros((3, 3)))
    root = np.diag(1 / np.sqrt(np.diag(M3)))
    shapes = root @ np.linalg.eigh(root @ K3 @ root)[1]
    for r in (1, 2, 3):
        assert _value(Modal.SHAPE, r, entries, 2, 0) == pytest.approx(
            shapes[2, r - 1] / shapes[0, r - 1], rel=1e-10)


def test_an_unstable_equilibrium_has_no_frequencies():
    entries = _entries(np.eye(2), [[-4.0, 0.0], [0.0, 9.0]], np.zeros((2, 2)))
    assert _value(Modal.STABLE, 1, entries) == 1.0
    assert np.isnan(_value(Modal.FREQUENCY, 1, entries))


def test_a_mode_that_moves_freely_has_a_zero_frequency_and_the_others_their_own():
    entries = _entries(np.eye(2), [[0.0, 0.0], [0.0, 9.0]], np.zeros((2, 2)))
    assert _value(Modal.STABLE, 1, entries) == 0.0
    assert [_value(Modal.FREQUENCY, r, entries) for r in (1, 2)] == [0.0, 3.0]


def test_an_overdamped_mode_has_the_damping_ratio_of_its_two_real_roots():
    entries = _entries(np.eye(2), np.diag([4.0, 9.0]), np.diag([5.0, 0.1]))  # zeta 1.25
    assert _value(Modal.PAIRED, 1, entries) == 0.0
    assert _value(Modal.DAMPING_RATIO, 1, entries) == pytest.approx(1.25, rel=1e-12)
    assert _value(Modal.DAMPING_RATIO, 2, entries) == pytest.approx(0.1 / 6, rel=1e-12)
    underdamped = _entries(np.eye(2), np.diag([4.0, 9.0]), np.diag([0.4, 0.6]))
    assert _value(Modal.DAMPING_RATIO, 2, underdamped) == pytest.approx(0.1, rel=1e-10)


# (k, m): numpy returns the critically damped pair off the real axis for 13.69 and 1
# (5.7e-8 j at 3.7 rad/s), as two real roots (-11.547005, 0.3e-6 apart) for 400 and 3, and as
# a double real root for 100 and 1
@pytest.mark.parametrize("k, m", [(13.69, 1.0), (400.0, 3.0), (100.0, 1.0), (1e4, 7.0),
                                  (3.0, 5.0)])
def test_a_critically_damped_block_has_a_damping_ratio_of_one(k, m):
    entries = _entries(np.eye(1), [[k / m]], [[2 * np.sqrt(k * m) / m]])
    assert _value(Modal.DAMPING_RATIO, 1, entries) == pytest.approx(1.0, rel=1e-9)
    assert _value(Modal.FREQUENCY, 1, entries) == pytest.approx(np.sqrt(k / m), rel=1e-12)


def test_the_damping_ratio_is_continuous_through_critical_damping():
    k, m = 13.69, 1.0
    for step in (-1e-6, -1e-9, 0.0, 1e-9, 1e-6, 0.5):
        c = 2 * np.sqrt(k * m) * (1 + step)
        entries = _entries(np.eye(1), [[k / m]], [[c / m]])
        assert _value(Modal.DAMPING_RATIO, 1, entries) == pytest.approx(1 + step, rel=1e-9)


def test_two_modes_that_do_not_vibrate_are_not_told_apart():
    # four real roots (-1, -4 and -0.5, -18): which two make a mode is not said by them
    entries = _entries(np.eye(2), np.diag([4.0, 9.0]), np.diag([5.0, 18.5]))
    assert _value(Modal.PAIRED, 1, entries) == 1.0
    assert np.isnan(_value(Modal.DAMPING_RATIO, 1, entries))
    assert _value(Modal.FREQUENCY, 2, entries) == 3.0


def test_a_free_mode_is_first_and_has_no_damping_ratio_the_others_keep_theirs():
    # a block on a damper alone beside a block on a spring and a damper: mode 1 moves freely
    entries = _entries(np.eye(2), np.diag([0.0, 9.0]), np.diag([2.0, 0.6]))
    assert [_value(Modal.FREQUENCY, r, entries) for r in (1, 2)] == [0.0, 3.0]
    assert [_value(Modal.FREE, r, entries) for r in (1, 2)] == [1.0, 0.0]
    assert np.isnan(_value(Modal.DAMPING_RATIO, 1, entries))
    assert _value(Modal.DAMPING_RATIO, 2, entries) == pytest.approx(0.1, rel=1e-12)
    undamped = _entries(np.eye(2), np.diag([0.0, 9.0]), np.diag([0.0, 0.6]))
    assert _value(Modal.FREE, 1, undamped) == 1.0
    assert _value(Modal.DAMPING_RATIO, 2, undamped) == pytest.approx(0.1, rel=1e-12)


def test_a_shape_relative_to_a_coordinate_that_does_not_move_has_no_value():
    entries = _entries(np.eye(2), np.diag([4.0, 9.0]), np.zeros((2, 2)))  # uncoupled
    assert _value(Modal.COUPLED, 1, entries, 0, 1) == 1.0
    assert np.isnan(_value(Modal.SHAPE, 1, entries, 0, 1))
    assert _value(Modal.COUPLED, 1, entries, 1, 0) == 0.0


def test_a_state_away_from_equilibrium_leaves_a_residual():
    assert _value(Modal.EQUILIBRIUM, 1, _entries(M3, K3, np.zeros((3, 3)))) == 0.0
    off = _entries(M3, K3, np.zeros((3, 3)), residual=[3.0, 0.0, 0.0])
    assert _value(Modal.EQUILIBRIUM, 1, off) > 0.0


def test_columns_of_entries_give_a_value_per_column():
    entries = _entries(np.eye(1), [[4.0]], [[0.0]])
    entries[3] = np.array([-4.0, -9.0, -16.0])  # db/dq: three stiffnesses
    assert modal_value(Modal.FREQUENCY, 1, 0, 0, 1, 1, *entries).tolist() == [2.0, 3.0, 4.0]


def test_the_sympy_function_evaluates_numbers_and_lambdifies_to_modal_value():
    k = sp.Symbol("k")
    entries = _entries(np.eye(1), [[1.0]], [[0.0]])
    entries[3] = -k
    mode = NaturalMode(Modal.FREQUENCY, 1, 0, 0, 1, 1, *entries)
    assert mode.subs(k, 25) == pytest.approx(5.0)
    f = sp.lambdify([k], mode, modules="numpy", cse=True)
    assert f(np.array([4.0, 9.0])).tolist() == [2.0, 3.0]


def test_a_constraint_kept_restricts_the_modes_to_the_motions_that_keep_it():
    # a block (x, 4 kg) on springs 600 and 300 N/m in series through a massless joint (xj):
    # the joint's balance -(k1 + k2) xj + k2 x = 0 is held, so the one mode is the block's on
    # k1 k2/(k1 + k2) = 200 N/m; without it the linearised motion has a spurious zero
    k1, k2, m = 600.0, 300.0, 4.0
    share = k2 / (k1 + k2)  # xj'' = share x'' from the balance at the acceleration level
    K = np.array([[k2 / m, -k2 / m], [share * k2 / m, -share * k2 / m]])  # rows x'', xj''
    zero = np.zeros((2, 2))
    entries = modal_entries(np.eye(2), np.zeros(2), [zero] * 2, [-K[:, j] for j in range(2)],
                            [zero] * 2, [np.zeros(2)] * 2, [[k2, -(k1 + k2)]])
    assert float(modal_value(Modal.FREQUENCY, 1, 0, 0, 2, 2, *entries)) == \
        pytest.approx(np.sqrt(k1 * k2 / (k1 + k2) / m), rel=1e-12)
    assert float(modal_value(Modal.SHAPE, 1, 1, 0, 2, 2, *entries)) == pytest.approx(share)
    assert float(modal_value(Modal.STABLE, 1, 0, 0, 2, 2, *entries)) == 0.0


@pytest.mark.parametrize("what", [Modal.FREQUENCY, Modal.DAMPING_RATIO, Modal.SHAPE,
                                  Modal.EQUILIBRIUM, Modal.STABLE])
def test_one_state_gives_what_its_column_among_others_gives(what):
    # one state (numbers, or arrays of one) is read without broadcasting: the same value, in
    # the shape the entries broadcast to, as when it is one column of several
    entries = _entries(M3, K3, np.diag([0.6, 0.4, 0.2]), residual=[0.3, 0.0, 0.0])
    alone = modal_value(what, 2, 1, 0, 3, 3, *entries)
    as_arrays = modal_value(what, 2, 1, 0, 3, 3, *(np.array([e]) for e in entries))
    mixed = [np.array([e]) if k % 2 else e for k, e in enumerate(entries)]
    among = modal_value(what, 2, 1, 0, 3, 3, *(np.array([e, 2 * e]) for e in entries))
    assert alone.shape == () and as_arrays.shape == (1,)
    assert modal_value(what, 2, 1, 0, 3, 3, *mixed).shape == (1,)
    assert float(alone) == as_arrays[0] == among[0]


def test_a_state_asked_again_gives_its_own_values():
    # the linearised modes are kept per state: a second state gets its own, the first again
    first, second = (_entries(np.eye(1), [[k]], [[0.0]]) for k in (4.0, 9.0))
    assert [_value(Modal.FREQUENCY, 1, e) for e in (first, second, first)] == [2.0, 3.0, 2.0]


def test_states_side_by_side_each_get_the_modes_they_get_alone():
    """A class's states worked out together (each entry a column of states) give each state
    what it gives alone, a state whose balances are singular or whose equilibrium is unstable
    among them (NaN, or the check that fails, at that state only)."""
    states = [_entries(M3, K3, 0.004 * K3), _entries(M3, -K3, np.zeros((3, 3))),
              _entries(np.zeros((3, 3)), K3, np.zeros((3, 3))),
              _entries(M3, K3, np.diag([12.0, 0.0, 0.0]))]
    columns = [np.array(entry, dtype=float) for entry in zip(*states)]
    for what in Modal:
        for number in (1, 3):
            together = modal_value(what, number, 2, 0, 3, 3, *columns)
            alone = [float(modal_value(what, number, 2, 0, 3, 3, *entries))
                     for entries in states]
            np.testing.assert_allclose(together, alone, rtol=1e-12, atol=0)
    frequency = modal_value(Modal.FREQUENCY, 1, 0, 0, 3, 3, *columns)
    assert np.isfinite(frequency).tolist() == [True, False, False, True]


def test_a_mode_that_moves_freely_but_for_round_off_has_a_zero_frequency():
    # a chain whose spring to the wall is left out: its free mode's squared frequency is
    # round-off (1e-14 beside 9), whose root (1e-7 rad/s) is no frequency
    entries = _entries(np.eye(2), [[1e-14, 0.0], [0.0, 9.0]], np.zeros((2, 2)))
    assert [_value(Modal.FREQUENCY, r, entries) for r in (1, 2)] == [0.0, 3.0]
    kept = _entries(np.eye(2), [[1e-8, 0.0], [0.0, 9.0]], np.zeros((2, 2)))
    assert _value(Modal.FREQUENCY, 1, kept) == pytest.approx(1e-4)
