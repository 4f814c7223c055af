"""solve_ivp: a whole run in one call, in the spirit of
scipy.integrate.solve_ivp."""
import numpy as np

from ._core import as_real
from ._errors import LignumError
from .integrator import Integrator


class Result:
    """The outputs of :func:`solve_ivp`.

    Attributes: ``t`` (n,), ``q`` (n, nq), ``v`` (n, nv), ``vdot`` (n, nv),
    ``lam`` (n, m; NaN at t0 before the first step), ``h`` and ``order`` (n,: the last step size and order
    at each output), ``t_events`` (list per event function of arrays of
    times), ``q_events``, ``v_events``, ``stats`` (dict), ``status`` (0:
    reached the end, 1: a terminal event, -1: failed), ``message``,
    ``success``, ``error`` (the LignumError of a failure, or None)."""

    def __repr__(self):
        return (f"Result(status={self.status}, message={self.message!r}, "
                f"{len(self.t)} outputs, t=[{self.t[0] if len(self.t) else ''} .. "
                f"{self.t[-1] if len(self.t) else ''}])")


def solve_ivp(model, t_span, t_eval=None, events=None,
              raise_on_failure=False, **settings):
    """Integrate ``model`` over ``t_span = (t0, tf)``.

    Parameters
    ----------
    model : Multibody or PythonModel
    t_span : (t0, tf)
    t_eval : array, optional
        Output times (increasing, inside t_span); default: every step.
    events : function or list of functions (t, q, v) -> float, optional
        Their zeros are located (``t_events``); a function with attribute
        ``terminal = True`` stops the run, ``direction`` (+1, -1, 0) selects
        the sign changes, as in scipy.
    raise_on_failure : bool
        Raise the LignumError instead of returning ``status = -1``.
    **settings
        Passed to :class:`Integrator` (method, rho_inf, step, adaptive,
        rtol, atol, kinematics, constraints, ...), and ``calc_ic`` ("q",
        "v", "qv") to make the initial state consistent first.

    Returns
    -------
    Result
    """
    if len(t_span) != 2:
        raise ValueError("t_span: expected (t0, tf)")
    t0, tf = as_real(t_span[0], "t_span[0]"), as_real(t_span[1], "t_span[1]")
    if not tf > t0:
        raise ValueError(f"t_span: need tf > t0, got ({t0}, {tf})")
    if t_eval is not None:
        t_eval = np.asarray(t_eval, dtype=np.float64).reshape(-1)
        if (not np.all(np.isfinite(t_eval)) or np.any(np.diff(t_eval) <= 0)
                or (t_eval.size and (t_eval[0] < t0 or t_eval[-1] > tf))):
            raise ValueError("t_eval: expected increasing finite times inside t_span")
    calc_ic = settings.pop("calc_ic", None)
    if events is None:
        events = []
    elif callable(events):
        events = [events]
    else:
        events = list(events)
    res = Result()
    ts, qs, vs, vdots, lams, hs, orders = [], [], [], [], [], [], []
    res.t_events = [[] for _ in events]
    res.q_events = [[] for _ in events]
    res.v_events = [[] for _ in events]
    res.status, res.message, res.error = 0, "reached the end of t_span", None
    with Integrator(model, t0=t0, **settings) as sim:
        if calc_ic is not None:
            sim.calc_ic(calc_ic)
        if events:
            sim.set_events(events, [int(getattr(e, "direction", 0)) for e in events])
        sim.set_stop_time(tf)

        def record():
            ts.append(sim.t)
            qs.append(sim.q.copy())
            vs.append(sim.v.copy())
            try:
                vdot, lam = sim.acceleration(), sim.multipliers()
            except LignumError:  # at t0: none computed before the first step
                vdot, lam = np.full(sim.nv, np.nan), np.full(sim.m, np.nan)
            vdots.append(vdot)
            lams.append(lam)
            if sim.stats["steps"]:
                hs.append(sim.last_step())
                orders.append(sim.last_order())
            else:
                hs.append(np.nan)
                orders.append(0)

        if t_eval is None or (t_eval.size and t_eval[0] == t0):
            record()
        targets = [tf] if t_eval is None else [t for t in t_eval if t > t0]
        try:
            for target in targets:
                while True:
                    status = sim.solve(target, one_step=t_eval is None)
                    if status == "root":
                        info = sim.root_info()
                        stop = False
                        for i, e in enumerate(events):
                            if info[i]:
                                res.t_events[i].append(sim.t)
                                res.q_events[i].append(sim.q.copy())
                                res.v_events[i].append(sim.v.copy())
                                stop = stop or bool(getattr(e, "terminal", False))
                        if stop:
                            res.status, res.message = 1, "a terminal event occurred"
                            record()
                            raise StopIteration
                        continue
                    if t_eval is None:
                        record()
                        if sim.t < tf:
                            continue
                    else:
                        record()
                    break
        except StopIteration:
            pass
        except LignumError as exc:
            if raise_on_failure:
                raise
            res.status, res.message, res.error = -1, str(exc), exc
        res.stats = sim.stats
        nq, nv, m = sim.nq, sim.nv, sim.m
    res.success = res.status >= 0
    res.t = np.array(ts)
    res.q = np.array(qs).reshape(len(ts), nq)
    res.v = np.array(vs).reshape(len(ts), nv)
    res.vdot = np.array(vdots).reshape(len(ts), nv)
    res.lam = np.array(lams).reshape(len(ts), m)
    res.h = np.array(hs)
    res.order = np.array(orders)
    res.t_events = [np.array(x) for x in res.t_events]
    res.q_events = [np.array(x) for x in res.q_events]
    res.v_events = [np.array(x) for x in res.v_events]
    return res
