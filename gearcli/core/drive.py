"""Prescribed time functions of a run: the drive (speed, motor angle or torque) and the load.

They are piecewise polynomials (:mod:`gearcli.core.timefunc`), evaluated exactly; the time loop
evaluates them once per stage time and hands plain numbers to :func:`gearcli.core.rhs.rhs`.
"""

from typing import NamedTuple

from gearcli.core.layout import DRIVE_TORQUE
from gearcli.core.nrt import jit_noalloc_inline
from gearcli.core.timefunc import pp_eval, pp_eval_d


class Forcing(NamedTuple):
    """Drive and load inputs at one time (see :func:`forcing`)."""

    angle: float  #: prescribed pinion / motor angle [rad] (0 in torque mode)
    value: float  #: omega(t) [rad/s] or T(t) [N*mm]
    rate: float  #: d omega/dt [rad/s^2] (0 in torque mode)
    load: float  #: T_load(t) [N*mm]


@jit_noalloc_inline
def forcing(t, mode, theta_offset, model):
    """Drive and load inputs at time ``t`` [s].

    Parameters
    ----------
    t : float
        Time [s].
    mode : int
        layout.DRIVE_SPEED, DRIVE_SHAFT or DRIVE_TORQUE.
    theta_offset : float
        ``theta1_init - Theta(t_start)`` [rad]: makes the prescribed angle start at theta1_init.
    model : gearcli.core.bundles.Model
        Its time functions (breaks, coefs, origins): ``drive_pp`` omega(t) [rad/s] (speed,
        shaft) or T(t) [N*mm] (torque), ``angle_pp`` its antiderivative Theta(t) [rad],
        ``load_pp`` the load torque T_load(t) [N*mm].

    Returns
    -------
    Forcing
        The prescribed angle is ``theta_offset + Theta(t)`` [rad].
    """
    drive_pp = model.drive_pp
    angle_pp = model.angle_pp
    load_pp = model.load_pp
    angle = 0.0
    rate = 0.0
    if mode == DRIVE_TORQUE:
        value = pp_eval(drive_pp[0], drive_pp[1], drive_pp[2], t)
    else:
        angle = theta_offset + pp_eval(angle_pp[0], angle_pp[1], angle_pp[2], t)
        value, rate = pp_eval_d(drive_pp[0], drive_pp[1], drive_pp[2], t)
    load = pp_eval(load_pp[0], load_pp[1], load_pp[2], t)
    return Forcing(angle, value, rate, load)
