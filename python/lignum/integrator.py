"""The integrator: Lignum's LGNCreate ... LGNSolve ... LGNFree in Python
style (one object, keyword settings, numpy arrays, exceptions)."""
import contextlib
import threading

import numpy as np

from ._core import System, as_int, as_real, as_vector, double_ptr
from ._errors import LignumError
from ._lignum import ffi, lib
from .model import Multibody

_KINEMATICS = {"simplified": lib.LGN_KINEMATICS_SIMPLIFIED, "exact": lib.LGN_KINEMATICS_EXACT,
               "sigma": lib.LGN_KINEMATICS_SIGMA}
_CONSTRAINTS = {"index3": lib.LGN_CONSTR_INDEX3, "index2": lib.LGN_CONSTR_INDEX2,
                "ggl": lib.LGN_CONSTR_GGL}
_NEWTON = {"full": lib.LGN_NEWTON_FULL, "modified": lib.LGN_NEWTON_MODIFIED}
_PROJECT = {"none": lib.LGN_PROJECT_NONE, "interpolated": lib.LGN_PROJECT_INTERPOLATED,
            "all": lib.LGN_PROJECT_ALL}
_IC = {"q": lib.LGN_IC_PROJECT_Q, "v": lib.LGN_IC_PROJECT_V, "qv": lib.LGN_IC_PROJECT_QV}
_STATS = (("steps", "LGNGetNumSteps"), ("newton_iters", "LGNGetNumNewtonIters"),
          ("newton_conv_fails", "LGNGetNumNewtonConvFails"), ("step_fails", "LGNGetNumStepFails"),
          ("err_test_fails", "LGNGetNumErrTestFails"), ("res_evals", "LGNGetNumResEvals"),
          ("jac_evals", "LGNGetNumJacEvals"), ("root_evals", "LGNGetNumGEvals"),
          ("output_solves", "LGNGetNumOutputSolves"))


def _choice(value, table, name):
    if value not in table:
        raise ValueError(f"{name}: expected one of {sorted(table)}, got {value!r}")
    return table[value]


class Integrator:
    """One Lignum integrator on a model, with the dense linear solver.

    Parameters
    ----------
    model : Multibody or PythonModel
    t0 : float
        Initial time.
    q0, v0 : arrays, optional
        Initial state (default: the model's).
    method : "genalpha", "newmark" or "bdf"
        Generalized-alpha (``rho_inf``, default 0.9, or all four of
        ``alpha_m``, ``alpha_f``, ``beta``, ``gamma``), Newmark (``beta``,
        ``gamma``, default 1/4, 1/2) or Lie group BDF up to order
        ``bdf_order`` (default 5). A parameter of another method is refused.
    kinematics : "simplified", "exact" or "sigma"
    constraints : "index3", "index2" or "ggl"
    step : float
        Fixed step size (required without ``adaptive``); with
        ``adaptive=True`` the first step tried (default: Lignum's estimate).
    adaptive : bool
        Error-controlled steps with ``rtol``, ``atol`` (default 1e-6 each),
        ``h0`` (first step), ``hmin``, ``hmax`` (refused without error
        control). With fixed steps ``rtol``, ``atol`` are the Newton
        iteration's tolerances (LGNSStolerances), Lignum's own by default.
    max_steps : int
        Steps allowed per :meth:`solve` call.
    newton : "full" or "modified"; max_newton_iters : int
    project_outputs : "all", "interpolated" or "none" (default: Lignum's)

    Every setting is checked here or by Lignum: a bad one raises
    TypeError/ValueError (Python side) or :class:`LignumError` with
    Lignum's flag name and message. The state ``q``, ``v`` are numpy arrays
    that Lignum updates in place (the N_Vectors wrap them, no copies).
    """

    def __init__(self, model, t0=0.0, q0=None, v0=None, method="genalpha", rho_inf=None,
                 alpha_m=None, alpha_f=None, beta=None, gamma=None, bdf_order=None,
                 kinematics=None, constraints=None, step=None, adaptive=False, rtol=None,
                 atol=None, h0=None, hmin=None, hmax=None, max_steps=100000, newton=None,
                 max_newton_iters=None, project_outputs=None):
        if not hasattr(model, "_build"):
            raise TypeError("model: expected a lignum.Multibody or lignum.PythonModel")
        if adaptive not in (True, False):
            raise TypeError(f"adaptive: expected True or False, got {adaptive!r}")
        # every setting acts or is refused: none that the method ignores
        unused = {"genalpha": ("bdf_order",), "bdf": ("rho_inf", "alpha_m", "alpha_f", "beta",
                                                      "gamma"),
                  "newmark": ("rho_inf", "alpha_m", "alpha_f", "bdf_order")}
        if method not in unused:
            raise ValueError(f"method: expected 'genalpha', 'newmark' or 'bdf', got {method!r}")
        given = dict(rho_inf=rho_inf, alpha_m=alpha_m, alpha_f=alpha_f, beta=beta, gamma=gamma,
                     bdf_order=bdf_order)
        for name in unused[method]:
            if given[name] is not None:
                raise ValueError(f"{name}: not a setting of method={method!r}")
        if not adaptive:
            for name, value in (("h0", h0), ("hmin", hmin), ("hmax", hmax)):
                if value is not None:
                    raise ValueError(f"{name}: only with adaptive=True (error control)")
        self.model = model
        self._sys = sys = System()
        t0 = as_real(t0, "t0")
        q_model, v_model = model._build(sys)
        p = sys.ptr
        nq, nv = p.nq, p.nv
        # the state arrays are owned here; the C vectors wrap them
        self._q = as_vector(q_model if q0 is None else q0, nq, "q0").copy()
        self._v = as_vector(v_model if v0 is None else v0, nv, "v0").copy()
        self._vdot = np.zeros(nv)
        self._lam = np.zeros(max(1, int(p.m)))
        cb = sys.callbacks
        mass_constant = True if isinstance(model, Multibody) else model.mass_constant
        if isinstance(model, Multibody):
            # m is known after the joints were added; size lambda before Attach
            self._lam = np.zeros(max(1, int(lib.LGNJoints_NumConstraints(p.joints))))
        sys.check(lib.LGNPy_Attach(p, t0, double_ptr(self._q), double_ptr(self._v),
                                   double_ptr(self._vdot), double_ptr(self._lam),
                                   1 if mass_constant else 0), "LGNInit")
        # Lignum writes them; Python only reads them (assigning would not
        # change the integrator's state: use a new Integrator or q0, v0)
        self._q.flags.writeable = False
        self._v.flags.writeable = False
        self._lock = threading.Lock()
        cb.nq, cb.nv, cb.m = nq, nv, p.m
        self.nq, self.nv, self.m = nq, nv, int(p.m)
        self.t = t0
        self._nroots = 0
        self._set_method(method, rho_inf, alpha_m, alpha_f, beta, gamma, bdf_order)
        mem = p.mem
        if kinematics is not None:
            sys.check(lib.LGNSetKinematics(mem, _choice(kinematics, _KINEMATICS, "kinematics")),
                      "LGNSetKinematics")
        if constraints is not None:
            sys.check(lib.LGNSetConstraintIndex(mem, _choice(constraints, _CONSTRAINTS,
                                                             "constraints")),
                      "LGNSetConstraintIndex")
        if adaptive:
            sys.check(lib.LGNSetStepControl(mem, lib.LGN_STEP_ADAPTIVE), "LGNSetStepControl")
        if adaptive or rtol is not None or atol is not None:
            rtol = 1e-6 if rtol is None else rtol
            atol = 1e-6 if atol is None else atol
            sys.check(lib.LGNSStolerances(mem, as_real(rtol, "rtol"), as_real(atol, "atol")),
                      "LGNSStolerances")
        if step is not None:
            sys.check(lib.LGNSetStepSize(mem, as_real(step, "step")), "LGNSetStepSize")
        if h0 is not None:
            sys.check(lib.LGNSetInitStep(mem, as_real(h0, "h0")), "LGNSetInitStep")
        if hmin is not None:
            sys.check(lib.LGNSetMinStep(mem, as_real(hmin, "hmin")), "LGNSetMinStep")
        if hmax is not None:
            sys.check(lib.LGNSetMaxStep(mem, as_real(hmax, "hmax")), "LGNSetMaxStep")
        sys.check(lib.LGNSetMaxNumSteps(mem, as_int(max_steps, "max_steps")),
                  "LGNSetMaxNumSteps")
        if newton is not None:
            sys.check(lib.LGNSetNewtonMode(mem, _choice(newton, _NEWTON, "newton")),
                      "LGNSetNewtonMode")
        if max_newton_iters is not None:
            sys.check(lib.LGNSetMaxNewtonIters(mem, as_int(max_newton_iters, "max_newton_iters")),
                      "LGNSetMaxNewtonIters")
        if project_outputs is not None:
            sys.check(lib.LGNSetProjectOutputs(mem, _choice(project_outputs, _PROJECT,
                                                            "project_outputs")),
                      "LGNSetProjectOutputs")

    def _set_method(self, method, rho_inf, alpha_m, alpha_f, beta, gamma, bdf_order):
        sys, mem = self._sys, self._sys.ptr.mem
        if method == "genalpha":
            params = (alpha_m, alpha_f, beta, gamma)
            if all(x is None for x in params):
                rho_inf = 0.9 if rho_inf is None else rho_inf
                sys.check(lib.LGNSetGenAlpha(mem, as_real(rho_inf, "rho_inf")), "LGNSetGenAlpha")
            elif any(x is None for x in params) or rho_inf is not None:
                raise ValueError("alpha_m, alpha_f, beta, gamma: give all four (and no "
                                 "rho_inf) or none")
            else:
                sys.check(lib.LGNSetGenAlphaParams(mem, *(as_real(x, n) for x, n in zip(
                    params, ("alpha_m", "alpha_f", "beta", "gamma")))), "LGNSetGenAlphaParams")
        elif method == "newmark":
            sys.check(lib.LGNSetNewmark(mem, as_real(0.25 if beta is None else beta, "beta"),
                                        as_real(0.5 if gamma is None else gamma, "gamma")),
                      "LGNSetNewmark")
        else:
            sys.check(lib.LGNSetBDF(mem, as_int(5 if bdf_order is None else bdf_order,
                                                "bdf_order")), "LGNSetBDF")

    # ---- running ----
    @property
    def q(self):
        """The configuration at :attr:`t`: a read-only numpy array that
        Lignum updates in place (the state N_Vector wraps it)."""
        return self._q

    @property
    def v(self):
        """The velocity at :attr:`t` (as :attr:`q`)."""
        return self._v

    def _mem(self):
        if self._sys.closed:
            raise ValueError("the integrator is closed")
        if self._lock.locked():
            raise RuntimeError("the integrator is running (a call from one of its own "
                               "callbacks, or from another thread)")
        return self._sys.ptr.mem

    @contextlib.contextmanager
    def _running(self):
        """Hold the integrator during a C call that runs callbacks."""
        if not self._lock.acquire(blocking=False):
            raise RuntimeError("the integrator is running (a call from one of its own "
                               "callbacks, or from another thread)")
        try:
            yield
        finally:
            self._lock.release()

    def solve(self, tout, one_step=False):
        """Integrate to ``tout`` (or one step towards it with
        ``one_step=True``); returns ``"tout"``, ``"tstop"`` or ``"root"``.
        The state is then in :attr:`t`, :attr:`q`, :attr:`v`. Raises
        :class:`LignumError` or the exception a Python callback raised;
        :attr:`t`, :attr:`q`, :attr:`v` then hold the state at the end of
        the last step that succeeded, as the step left it (not projected
        onto the constraints; the failed step is undone)."""
        mem = self._mem()
        tout = as_real(tout, "tout")
        tret = ffi.new("double *", self.t)
        p = self._sys.ptr
        with self._running():
            flag = lib.LGNSolve(mem, tout, tret, p.q, p.v,
                                lib.LGN_ONE_STEP if one_step else lib.LGN_NORMAL)
            # also after a failure: q, v then hold the state at the last
            # step's end, tret its time
            self.t = tret[0]
            self._sys.check(flag, "LGNSolve")
        if flag == lib.LGN_ROOT_RETURN:
            return "root"
        if flag == lib.LGN_TSTOP_RETURN:
            return "tstop"
        return "tout" if not one_step else "step"

    def set_stop_time(self, tstop):
        """Never step past ``tstop`` (LGNSetStopTime)."""
        self._sys.check(lib.LGNSetStopTime(self._mem(), as_real(tstop, "tstop")),
                        "LGNSetStopTime")

    def clear_stop_time(self):
        """Remove the stop time (LGNClearStopTime)."""
        self._sys.check(lib.LGNClearStopTime(self._mem()), "LGNClearStopTime")

    def calc_ic(self, which="v"):
        """Make the initial state consistent (LGNCalcIC): project ``"q"``,
        ``"v"`` or both (``"qv"``); :attr:`q`, :attr:`v` then hold it."""
        mem = self._mem()
        icopt = _choice(which, _IC, "which")
        with self._running():
            self._sys.check(lib.LGNCalcIC(mem, icopt), "LGNCalcIC")
        p = self._sys.ptr
        self._sys.check(lib.LGNGetConsistentIC(mem, p.q, p.v), "LGNGetConsistentIC")

    def set_events(self, functions, direction=None):
        """Root functions g_i(t, q, v) -> float located by Lignum
        (LGNRootInit); :meth:`solve` then returns ``"root"`` at a zero.
        ``direction``: per function +1 (increasing only), -1, 0 (both).
        An empty list removes them."""
        fns = list(functions)
        for f in fns:
            if not callable(f):
                raise TypeError(f"functions: {f!r} is not callable")
        mem = self._mem()
        cb = self._sys.callbacks
        n = len(fns)
        if n:
            cb.vec[lib.LGNPY_CB_ROOT] = lambda t, q, v: [f(t, q, v) for f in fns]
        cb.nroots = n
        self._sys.check(lib.LGNPy_RootInit(self._sys.ptr, n), "LGNRootInit")
        self._nroots = n
        if direction is not None and n:
            d = np.array(direction, dtype=np.intc)
            if d.shape != (n,) or not np.all(np.isin(d, (-1, 0, 1))):
                raise ValueError(f"direction: expected {n} values of -1, 0, +1")
            self._sys.check(lib.LGNSetRootDirection(mem, ffi.cast("int *", ffi.from_buffer(d))),
                            "LGNSetRootDirection")

    def root_info(self):
        """After ``"root"``: per root function 0, or +1 / -1 (its sign change)."""
        out = np.zeros(self._nroots, dtype=np.intc)
        if self._nroots:
            self._sys.check(lib.LGNGetRootInfo(self._mem(), ffi.cast("int *",
                                                                     ffi.from_buffer(out))),
                            "LGNGetRootInfo")
        return out

    # ---- outputs ----
    def acceleration(self):
        """vdot at the last output (LGNGetAcceleration), a new array."""
        self._sys.check(lib.LGNGetAcceleration(self._mem(), self._sys.ptr.vdot),
                        "LGNGetAcceleration")
        return self._vdot.copy()

    def multipliers(self):
        """lambda at the last output (LGNGetMultipliers), a new array (empty
        without constraints)."""
        if self.m == 0:
            return np.zeros(0)
        self._sys.check(lib.LGNGetMultipliers(self._mem(), getattr(self._sys.ptr, "lambda")),
                        "LGNGetMultipliers")
        return self._lam[:self.m].copy()

    def last_step(self):
        """Size of the last step taken (LGNGetLastStep)."""
        h = ffi.new("double *")
        self._sys.check(lib.LGNGetLastStep(self._mem(), h), "LGNGetLastStep")
        return h[0]

    def last_order(self):
        """Order of the last step (BDF; 2 for the Newmark family)."""
        k = ffi.new("int *")
        self._sys.check(lib.LGNGetLastOrder(self._mem(), k), "LGNGetLastOrder")
        return k[0]

    @property
    def stats(self):
        """Counters: steps, newton_iters, newton_conv_fails, step_fails,
        err_test_fails, res_evals, jac_evals, root_evals, output_solves."""
        mem = self._mem()
        out, n = {}, ffi.new("long *")
        for key, fn in _STATS:
            self._sys.check(getattr(lib, fn)(mem, n), fn)
            out[key] = n[0]
        return out

    def energy(self, q=None, v=None):
        """(kinetic, potential) energy of a Multibody at q, v (default: the
        current state)."""
        self._mem()
        if not isinstance(self.model, Multibody):
            raise TypeError("energy: only for a lignum.Multibody")
        return self.model.energy(self._sys, self.q if q is None else q,
                                 self.v if v is None else v)

    def constraint_residual(self, q=None, t=None):
        """Phi(q, t) of a Multibody's joints (default: the current state)."""
        self._mem()
        if not isinstance(self.model, Multibody):
            raise TypeError("constraint_residual: only for a lignum.Multibody")
        if self.m == 0:
            return np.zeros(0)
        q = as_vector(self.q if q is None else q, self.nq, "q")
        phi = np.zeros(self.m)
        self._sys.check(lib.LGNPy_Residual(self._sys.ptr, as_real(self.t if t is None else t, "t"),
                                           double_ptr(q), double_ptr(phi)), "LGNJoints_Residual")
        return phi

    def close(self):
        """Free the C integrator and model now (also done when collected)."""
        if hasattr(self, "_lock") and self._lock.locked():
            raise RuntimeError("close: the integrator is running")
        self._sys.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
