"""Low-level helpers shared by the model and integrator classes: the cffi
library, flag checks, array conversion and the Python side of the
callbacks."""
import threading
import warnings

import numpy as np

from ._errors import LignumError, LignumWarning
from ._lignum import ffi, lib

GROUND = lib.LGN_GROUND


def flag_name(flag):
    """Name of a Lignum return flag, e.g. ``flag_name(-22) == "LGN_ILL_INPUT"``."""
    return ffi.string(lib.LGNGetReturnFlagName(int(flag))).decode()


def as_vector(x, n, name, finite=True):
    """``x`` as a contiguous float64 array of length ``n`` (a copy only when
    its layout or type differs); raises TypeError or ValueError naming
    ``name``."""
    try:
        a = np.ascontiguousarray(x, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name}: expected {n} real numbers, got {x!r}") from exc
    if a.ndim == 0 and n == 1:
        a = a.reshape(1)
    if a.shape != (n,):
        raise ValueError(f"{name}: expected shape ({n},), got {a.shape}")
    if finite and not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: contains NaN or Inf")
    return a


def as_real(x, name, positive=False, nonnegative=False):
    """``x`` as a finite float; raises TypeError or ValueError naming ``name``."""
    if isinstance(x, (str, bytes)) or x is None:
        raise TypeError(f"{name}: expected a real number, got {x!r}")
    try:
        r = float(x)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name}: expected a real number, got {x!r}") from exc
    if not np.isfinite(r):
        raise ValueError(f"{name}: must be finite, got {r}")
    if positive and r <= 0.0:
        raise ValueError(f"{name}: must be > 0, got {r}")
    if nonnegative and r < 0.0:
        raise ValueError(f"{name}: must be >= 0, got {r}")
    return r


def as_int(x, name):
    """``x`` as an int (bool and float refused)."""
    if isinstance(x, bool) or not isinstance(x, (int, np.integer)):
        raise TypeError(f"{name}: expected an integer, got {x!r}")
    return int(x)


def double_ptr(a):
    """A ``double *`` into the data of the float64 array ``a`` (no copy)."""
    return ffi.cast("double *", ffi.from_buffer(a))


class Callbacks:
    """The Python functions behind a system's callbacks, reached from C
    through a cffi handle. Holds no reference to the integrator (no cycle).
    The first exception a function raises is kept in ``error`` and raised
    again by the Python call that ran the integrator."""

    def __init__(self):
        self.vec = {}        # which -> (function, sizes of q, v, out)
        self.mat = {}        # which -> (function, sizes, matrix shape)
        self.drives = []     # Python drive laws, by driver number
        self.nq = self.nv = self.m = self.nroots = 0
        self.error = None

    def raise_pending(self):
        """Raise the exception a callback raised, if any (and clear it)."""
        if self.error is not None:
            exc, self.error = self.error, None
            raise exc


_views = {}


def _view(ptr, n, writeable=True):
    """A numpy array on n doubles at ptr (no copy); read-only for a
    callback's inputs (t, q, v, ...: writing them would change Lignum's
    state behind its back), writeable for its output. Lignum passes the
    same few work vectors again and again: the arrays are cached by
    address, length and mode (a bounded cache: cleared past 256 entries)."""
    if ptr == ffi.NULL or n == 0:
        return None
    key = (int(ffi.cast("uintptr_t", ptr)), n, writeable)
    a = _views.get(key)
    if a is None:
        if len(_views) > 256:
            _views.clear()
        a = np.frombuffer(ffi.buffer(ptr, 8 * n), dtype=np.float64)
        a.flags.writeable = writeable
        _views[key] = a
    return a


# The exception a Python callback raised, per thread: cffi's onerror hook
# does not see the handle, and a callback runs in the thread that called
# the C function (cffi releases the GIL during C calls, so two integrators
# may run in two threads; one integrator must not be shared by threads).
_pending = threading.local()


def _on_error(exception, exc_value, traceback):
    # keep the first exception of the C call; the callback returns -1
    # (unrecoverable), the C call fails, System.check raises it again
    if getattr(_pending, "exc", None) is None:
        _pending.exc = exc_value if exc_value is not None else exception()
    return -1


def take_pending():
    """The exception a callback raised during the last C call of this
    thread, or None (and clear it)."""
    exc = getattr(_pending, "exc", None)
    _pending.exc = None
    return exc


@ffi.def_extern(error=-1, onerror=_on_error)
def lgnpy_vec_cb(handle, which, t, q, v, out):
    cb = ffi.from_handle(handle)
    nq, nv = cb.nq, cb.nv
    if which == lib.LGNPY_CB_ROOT:
        nout = cb.nroots
    elif which in (lib.LGNPY_CB_CONSTR, lib.LGNPY_CB_CURVATURE, lib.LGNPY_CB_CONSTR_TIME):
        nout = cb.m
    else:
        nout = nv
    fn = cb.vec[which]
    outv = _view(out, nout)
    if which == lib.LGNPY_CB_ROOT:
        outv[:] = fn(t, _view(q, nq, False), _view(v, nv, False))
        return 0
    if v == ffi.NULL:
        fn(t, _view(q, nq, False), outv)
    else:
        fn(t, _view(q, nq, False), _view(v, nv, False), outv)
    return 0


@ffi.def_extern(error=-1, onerror=_on_error)
def lgnpy_mat_cb(handle, which, t, q, v, vdot, lam, mat):
    cb = ffi.from_handle(handle)
    nq, nv, m = cb.nq, cb.nv, cb.m
    rows = m if which == lib.LGNPY_CB_JAC else nv
    M = _view(mat, rows * nv).reshape((rows, nv), order="F")
    fn = cb.mat[which]
    if which in (lib.LGNPY_CB_MASS, lib.LGNPY_CB_JAC):
        fn(t, _view(q, nq, False), M)
    elif which in (lib.LGNPY_CB_DAMPING, lib.LGNPY_CB_APPLIED_DQ, lib.LGNPY_CB_APPLIED_DV):
        fn(t, _view(q, nq, False), _view(v, nv, False), M)
    else:
        fn(t, _view(q, nq, False), _view(v, nv, False), _view(vdot, nv, False),
           _view(lam, m, False), M)
    return 0


@ffi.def_extern(error=-1, onerror=_on_error)
def lgnpy_drive_cb(handle, index, t, f):
    cb = ffi.from_handle(handle)
    value = cb.drives[index](t)
    out = _view(f, 3)
    out[:] = value
    if not np.all(np.isfinite(out)):
        raise ValueError(f"drive law {index}: returned a non-finite value {tuple(out)}")
    return 0


class System:
    """Owner of one C record (``LGNPySystem``): frees it when collected or
    closed. Every C call goes through :meth:`check`."""

    def __init__(self):
        self.callbacks = Callbacks()
        self._handle = ffi.new_handle(self.callbacks)
        ptr = lib.LGNPy_Create(self._handle)
        if ptr == ffi.NULL:
            raise MemoryError("LGNPy_Create: no memory for the SUNDIALS context")
        self.ptr = ffi.gc(ptr, lib.LGNPy_Free)
        self.closed = False

    def close(self):
        """Free the C record now (idempotent)."""
        if not self.closed:
            self.closed = True
            ffi.release(self.ptr)

    def check(self, flag, call=""):
        """Raise a pending callback exception, or LignumError for a negative
        flag; emit Lignum's warnings. Returns the flag."""
        p = self.ptr
        exc = take_pending()
        if p.nwarnings:
            for text in ffi.string(p.warnings).decode(errors="replace").split("\n"):
                warnings.warn(text, LignumWarning, stacklevel=3)
        if exc is not None:
            lib.LGNPy_ClearError(p)
            raise exc
        if flag < 0:
            function = ffi.string(p.err_function).decode(errors="replace") or call
            message = ffi.string(p.err_msg).decode(errors="replace")
            lib.LGNPy_ClearError(p)
            raise LignumError(flag, flag_name(flag), function, message)
        lib.LGNPy_ClearError(p)
        return flag
