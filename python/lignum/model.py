"""Models: rigid bodies, joints, spring-dampers and drivers integrated in C
(:class:`Multibody`), or a model written as Python functions
(:class:`PythonModel`)."""
import math

import numpy as np

from ._core import GROUND, as_int, as_real, as_vector, double_ptr
from ._lignum import ffi, lib


def quaternion(axis, angle):
    """Unit quaternion (w, x, y, z) of a rotation by ``angle`` (radians)
    about ``axis`` (any nonzero length), the layout of q on SO(3)."""
    n = as_vector(axis, 3, "axis")
    norm = math.sqrt(float(n @ n))
    if norm == 0.0:
        raise ValueError("axis: must be nonzero")
    angle = as_real(angle, "angle")
    s = math.sin(0.5 * angle)
    return np.array([math.cos(0.5 * angle), s * n[0] / norm, s * n[1] / norm, s * n[2] / norm])


def polynomial(c0=0.0, c1=0.0, c2=0.0, c3=0.0):
    """Drive law f(t) = c0 + c1 t + c2 t^2 + c3 t^3, evaluated in C."""
    return (lib.LGNPY_DRIVE_POLYNOMIAL,
            [as_real(c, f"c{i}") for i, c in enumerate((c0, c1, c2, c3))])


def harmonic(offset=0.0, amplitude=1.0, omega=1.0, phase=0.0):
    """Drive law f(t) = offset + amplitude sin(omega t + phase), evaluated in C."""
    return (lib.LGNPY_DRIVE_HARMONIC,
            [as_real(offset, "offset"), as_real(amplitude, "amplitude"),
             as_real(omega, "omega"), as_real(phase, "phase")])


class Multibody:
    """Rigid bodies on (R^3 x SO(3))^n with joints, spring-dampers, drivers
    and gravity; every callback runs in C (the model object ``LGNModel`` on
    the sets ``LGNBodies``, ``LGNJoints``). Planar mechanisms:
    :class:`PlanarMultibody`.

    Body k has q = (x, p): the centre of mass x (inertial) and the unit
    quaternion p = (w, x, y, z) of its rotation R; v = (u, Omega): the
    inertial velocity of the centre of mass and the body-frame angular
    velocity. Points ``s`` on a body are in its body frame (centre of mass
    at the origin); on :data:`GROUND` they are inertial.

    Parameters
    ----------
    gravity : 3 reals, optional
        The gravitational acceleration (inertial), default none.
    """

    _group = lib.LGNPY_GROUP_R3XSO3

    def __init__(self, gravity=(0.0, 0.0, 0.0)):
        self.gravity = as_vector(gravity, 3, "gravity")
        self._bodies = []
        self._items = []      # (kind, arguments) in the order of the calls
        self.applied_force = None
        self.applied_force_dq = None
        self.applied_force_dv = None

    @property
    def nbodies(self):
        """Number of bodies."""
        return len(self._bodies)

    def add_body(self, mass, inertia, position=(0.0, 0.0, 0.0), rotation=(1.0, 0.0, 0.0, 0.0),
                 velocity=(0.0, 0.0, 0.0), angular_velocity=(0.0, 0.0, 0.0)):
        """Add a rigid body; returns its index.

        mass > 0; inertia: 3 principal moments (body axes) or a 3x3 matrix
        about the centre of mass; position: x; rotation: the quaternion p
        (w, x, y, z) (normalised by Lignum's group); velocity: u (inertial);
        angular_velocity: Omega (body frame)."""
        mass = as_real(mass, "mass", positive=True)
        J = np.asarray(inertia, dtype=np.float64) if not isinstance(inertia, str) else None
        if J is None or J.shape not in ((3,), (3, 3)):
            raise ValueError("inertia: expected 3 principal moments or a 3x3 matrix")
        if not np.all(np.isfinite(J)):
            raise ValueError("inertia: contains NaN or Inf")
        body = dict(mass=mass, inertia=np.ascontiguousarray(J.reshape(-1)),
                    position=as_vector(position, 3, "position"),
                    rotation=as_vector(rotation, 4, "rotation"),
                    velocity=as_vector(velocity, 3, "velocity"),
                    angular_velocity=as_vector(angular_velocity, 3, "angular_velocity"))
        self._bodies.append(body)
        return len(self._bodies) - 1

    def _body(self, k, name):
        k = as_int(k, name)
        if k != GROUND and not 0 <= k < len(self._bodies):
            raise ValueError(f"{name}: no body {k} (bodies 0..{len(self._bodies) - 1} "
                             "or lignum.GROUND)")
        return k

    def _joint(self, kind, a, sa, axis_a, b, sb, axis_b):
        a, b = self._body(a, "a"), self._body(b, "b")
        args = [a, as_vector(sa, 3, "sa")]
        if axis_a is not None:
            args.append(as_vector(axis_a, 3, "axis_a"))
        args += [b, as_vector(sb, 3, "sb")]
        if axis_b is not None:
            args.append(as_vector(axis_b, 3, "axis_b"))
        self._items.append((kind, args))

    def spherical(self, a, sa, b, sb):
        """Spherical joint: point sa of body a coincides with sb of b (3 rows)."""
        self._joint("spherical", a, sa, None, b, sb, None)

    def revolute(self, a, sa, axis_a, b, sb, axis_b):
        """Revolute joint about axis_a of a = axis_b of b at sa = sb (5 rows)."""
        self._joint("revolute", a, sa, axis_a, b, sb, axis_b)

    def universal(self, a, sa, axis_a, b, sb, axis_b):
        """Universal joint: sa = sb, axis_a perpendicular to axis_b (4 rows)."""
        self._joint("universal", a, sa, axis_a, b, sb, axis_b)

    def prismatic(self, a, sa, axis_a, b, sb, axis_b):
        """Prismatic joint: sliding along axis_a = axis_b, no rotation (5 rows)."""
        self._joint("prismatic", a, sa, axis_a, b, sb, axis_b)

    def cylindrical(self, a, sa, axis_a, b, sb, axis_b):
        """Cylindrical joint: sliding and turning about axis_a = axis_b (4 rows)."""
        self._joint("cylindrical", a, sa, axis_a, b, sb, axis_b)

    def spring_damper(self, a, sa, b, sb, k, c, length):
        """Translational spring-damper between points sa of a and sb of b:
        stiffness k, damping c, rest length."""
        self._items.append(("spring", [self._body(a, "a"), as_vector(sa, 3, "sa"),
                                       self._body(b, "b"), as_vector(sb, 3, "sb"),
                                       as_real(k, "k"), as_real(c, "c"),
                                       as_real(length, "length")]))

    def rotational_spring_damper(self, a, b, k, c, rest=(1.0, 0.0, 0.0, 0.0)):
        """Rotational spring-damper between the frames of a and b: stiffness
        k, damping c, rest relative rotation (a quaternion)."""
        self._items.append(("rotspring", [self._body(a, "a"), self._body(b, "b"),
                                          as_real(k, "k"), as_real(c, "c"),
                                          as_vector(rest, 4, "rest")]))

    @staticmethod
    def _law(law):
        if callable(law):
            return lib.LGNPY_DRIVE_PYTHON, [0.0] * 4, law
        try:
            kind, coeffs = law
            ok = kind in (lib.LGNPY_DRIVE_POLYNOMIAL, lib.LGNPY_DRIVE_HARMONIC) and \
                len(coeffs) == 4
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise TypeError("law: expected lignum.polynomial(...), lignum.harmonic(...) "
                            "or a function t -> (f, f', f'')")
        return kind, [as_real(c, "law") for c in coeffs], None

    def rotation_driver(self, a, axis_a, ref_a, b, ref_b, law):
        """Prescribed angle f(t) of direction ref_b of b about axis_a of a
        from ref_a (1 row; with a revolute joint: a motor). ``law``:
        :func:`polynomial`, :func:`harmonic` (both in C) or a Python
        function ``t -> (f, f', f'')``."""
        self._items.append(("rotdriver", [self._body(a, "a"), as_vector(axis_a, 3, "axis_a"),
                                          as_vector(ref_a, 3, "ref_a"), self._body(b, "b"),
                                          as_vector(ref_b, 3, "ref_b"), self._law(law)]))

    def translation_driver(self, a, sa, axis_a, b, sb, law):
        """Prescribed distance f(t) of sb of b from sa of a along axis_a
        (1 row; with a prismatic joint: an actuator). ``law`` as for
        :meth:`rotation_driver`."""
        self._items.append(("transdriver", [self._body(a, "a"), as_vector(sa, 3, "sa"),
                                            as_vector(axis_a, 3, "axis_a"), self._body(b, "b"),
                                            as_vector(sb, 3, "sb"), self._law(law)]))

    def initial_state(self):
        """(q0, v0) from the bodies' positions, rotations and velocities."""
        q = np.concatenate([np.concatenate([b["position"], b["rotation"]]) for b in self._bodies])
        v = np.concatenate([np.concatenate([b["velocity"], b["angular_velocity"]])
                            for b in self._bodies])
        return q, v

    def _build(self, system):
        """Create the C body and joint sets in ``system`` (an internal
        ``_core.System``)."""
        if not self._bodies:
            raise ValueError("Multibody: add at least one body")
        p = system.ptr
        system.check(lib.LGNPy_MultibodyInit(p, len(self._bodies), self._group),
                     "LGNPy_MultibodyInit")
        keep = []  # arrays alive during the calls

        def ptr(a):
            keep.append(a)
            return double_ptr(a)

        for k, b in enumerate(self._bodies):
            if b["inertia"].size == 3:
                flag = lib.LGNBodies_SetPrincipalInertia(p.bodies, k, b["mass"], ptr(b["inertia"]))
            else:
                flag = lib.LGNBodies_SetMass(p.bodies, k, b["mass"], ptr(b["inertia"]))
            system.check(flag, "LGNBodies_SetMass")
        if np.any(self.gravity != 0.0):
            system.check(lib.LGNBodies_SetGravity(p.bodies, ptr(self.gravity)),
                         "LGNBodies_SetGravity")
        joint_fns = {"spherical": lib.LGNJoints_AddSpherical, "revolute": lib.LGNJoints_AddRevolute,
                     "universal": lib.LGNJoints_AddUniversal,
                     "prismatic": lib.LGNJoints_AddPrismatic,
                     "cylindrical": lib.LGNJoints_AddCylindrical}
        cb = system.callbacks
        for kind, args in self._items:
            if kind in joint_fns:
                cargs = [ptr(x) if isinstance(x, np.ndarray) else x for x in args]
                system.check(joint_fns[kind](p.joints, *cargs), f"LGNJoints_Add({kind})")
            elif kind == "spring":
                a, sa, b, sb, k, c, L0 = args
                system.check(lib.LGNBodies_AddSpringDamper(p.bodies, a, ptr(sa), b, ptr(sb), k, c,
                                                           L0), "LGNBodies_AddSpringDamper")
            elif kind == "rotspring":
                a, b, k, c, rest = args
                system.check(lib.LGNBodies_AddRotationalSpringDamper(p.bodies, a, b, k, c,
                                                                     ptr(rest)),
                             "LGNBodies_AddRotationalSpringDamper")
            else:
                self._add_driver(system, kind, args, ptr)
        self._set_applied_force(system)
        return self.initial_state()

    @staticmethod
    def _add_driver(system, kind, args, ptr):
        """A driver item: rotation (a, axis_a, ref_a, b, ref_b, law) or
        translation (a, sa, axis_a, b, sb, law); on a planar model the
        references are None (LGNPy_AddDriver picks the planar function)."""
        p = system.ptr

        def opt(x):
            return ffi.NULL if x is None else ptr(x)

        (lawkind, coeffs, fn) = args[-1]
        c = ptr(np.array(coeffs, dtype=np.float64))
        if kind == "rotdriver":
            a, axis_a, ref_a, b, ref_b = args[:5]
            flag = lib.LGNPy_AddDriver(p, 1, a, ffi.NULL, opt(axis_a), opt(ref_a), b, ffi.NULL,
                                       opt(ref_b), lawkind, c)
        else:
            a, sa, axis_a, b, sb = args[:5]
            flag = lib.LGNPy_AddDriver(p, 0, a, ptr(sa), ptr(axis_a), ffi.NULL, b, ptr(sb),
                                       ffi.NULL, lawkind, c)
        system.check(flag, "LGNJoints_AddDriver")
        system.callbacks.drives.append(fn)

    def _set_applied_force(self, system):
        """The Python applied force, given to the model as its user force
        (LGNModel_SetUserForce) with its Jacobians when set."""
        f, dq, dv = self.applied_force, self.applied_force_dq, self.applied_force_dv
        if f is None:
            if dq is not None or dv is not None:
                raise TypeError("applied_force_dq, applied_force_dv: need an applied_force")
            return
        if not callable(f):
            raise TypeError("applied_force: expected a function (t, q, v, f) or None")
        for name, fn in (("applied_force_dq", dq), ("applied_force_dv", dv)):
            if fn is not None and not callable(fn):
                raise TypeError(f"{name}: expected a function (t, q, v, D) or None")
        cb = system.callbacks
        cb.vec[lib.LGNPY_CB_APPLIED] = f
        cb.mat[lib.LGNPY_CB_APPLIED_DQ] = dq
        cb.mat[lib.LGNPY_CB_APPLIED_DV] = dv
        system.check(lib.LGNPy_SetAppliedForce(system.ptr, 1, dq is not None, dv is not None),
                     "LGNModel_SetUserForce")

    def energy(self, system, q, v):
        """(kinetic, potential) energy at q, v (internal; see
        Integrator.energy)."""
        kin, pot = ffi.new("double *"), ffi.new("double *")
        q = as_vector(q, system.ptr.nq, "q")
        v = as_vector(v, system.ptr.nv, "v")
        system.check(lib.LGNPy_Energy(system.ptr, double_ptr(q), double_ptr(v), kin, pot),
                     "LGNBodies_Energy")
        return kin[0], pot[0]


class PlanarMultibody(Multibody):
    """A planar mechanism: rigid bodies moving in the x-y plane on (SE(2))^n
    or (R^2 x SO(2))^n with planar joints, spring-dampers, drivers and
    gravity; every callback runs in C (``LGNModel`` on planar sets,
    lignum_planar.h).

    Body k has q = (x, y, theta): the centre of mass and the angle theta
    (a real number that counts turns). v = (U, omega) on ``"SE2"``, with U
    the velocity of the centre of mass in the body frame; v = (u, omega) on
    ``"R2xSO2"``, u inertial. Points ``s`` on a body are 2-vectors in its
    body frame (centre of mass at the origin); on :data:`GROUND` they are
    inertial.

    Parameters
    ----------
    gravity : 2 reals, optional
        The gravitational acceleration in the plane, default none.
    group : ``"SE2"`` (default) or ``"R2xSO2"``
        The group of each body.
    """

    _PLANAR_GROUPS = {"SE2": lib.LGNPY_GROUP_SE2, "R2xSO2": lib.LGNPY_GROUP_R2XSO2}

    def __init__(self, gravity=(0.0, 0.0), group="SE2"):
        if not isinstance(group, str) or group not in self._PLANAR_GROUPS:
            raise ValueError(f"group: expected 'SE2' or 'R2xSO2', got {group!r}")
        super().__init__()
        self.group = group
        self._group = self._PLANAR_GROUPS[group]
        self.gravity = np.concatenate([as_vector(gravity, 2, "gravity"), [0.0]])

    def add_body(self, mass, inertia, position=(0.0, 0.0), angle=0.0, velocity=(0.0, 0.0),
                 angular_velocity=0.0):
        """Add a rigid body; returns its index.

        mass > 0; inertia > 0: the moment of inertia about the centre of
        mass (normal to the plane); position: (x, y); angle: theta
        (radians); velocity: the velocity part of v (body-fixed U on SE2,
        inertial u on R2xSO2); angular_velocity: omega."""
        body = dict(mass=as_real(mass, "mass", positive=True),
                    inertia=as_real(inertia, "inertia", positive=True),
                    position=as_vector(position, 2, "position"), angle=as_real(angle, "angle"),
                    velocity=as_vector(velocity, 2, "velocity"),
                    angular_velocity=as_real(angular_velocity, "angular_velocity"))
        self._bodies.append(body)
        return len(self._bodies) - 1

    def revolute(self, a, sa, b, sb):
        """Planar revolute joint: point sa of body a coincides with sb of b
        (2 rows; the multipliers are the joint force on b, inertial)."""
        self._items.append(("revolute", [self._body(a, "a"), as_vector(sa, 2, "sa"),
                                         self._body(b, "b"), as_vector(sb, 2, "sb")]))

    def prismatic(self, a, sa, axis_a, b, sb, angle=0.0):
        """Planar prismatic joint: point sb of b slides on the line through
        sa of a along axis_a (body a's frame, nonzero), and the relative
        angle is locked, theta_b - theta_a = angle (2 rows)."""
        self._items.append(("prismatic", [self._body(a, "a"), as_vector(sa, 2, "sa"),
                                          as_vector(axis_a, 2, "axis_a"), self._body(b, "b"),
                                          as_vector(sb, 2, "sb"), as_real(angle, "angle")]))

    def spherical(self, *args):
        raise TypeError("spherical: not a planar joint (PlanarMultibody has revolute and "
                        "prismatic joints)")

    universal = cylindrical = spherical

    def spring_damper(self, a, sa, b, sb, k, c, length):
        """Translational spring-damper between points sa of a and sb of b
        (2-vectors): tension k (L - length) + c dL/dt; k, c, length >= 0."""
        self._items.append(("spring", [self._body(a, "a"), as_vector(sa, 2, "sa"),
                                       self._body(b, "b"), as_vector(sb, 2, "sb"),
                                       as_real(k, "k"), as_real(c, "c"),
                                       as_real(length, "length")]))

    def rotational_spring_damper(self, a, b, k, c, rest=0.0):
        """Rotational spring-damper between a and b: torque -k (theta_b -
        theta_a - rest) - c (omega_b - omega_a) on b, the reaction on a."""
        self._items.append(("rotspring", [self._body(a, "a"), self._body(b, "b"),
                                          as_real(k, "k"), as_real(c, "c"),
                                          as_real(rest, "rest")]))

    def rotation_driver(self, a, b, law):
        """Prescribed relative angle theta_b - theta_a = f(t) (1 row; with a
        revolute joint: a motor). ``law``: :func:`polynomial`,
        :func:`harmonic` (both in C) or a Python function
        ``t -> (f, f', f'')``."""
        self._items.append(("rotdriver", [self._body(a, "a"), None, None, self._body(b, "b"),
                                          None, self._law(law)]))

    def translation_driver(self, a, sa, axis_a, b, sb, law):
        """Prescribed distance f(t) of point sb of b from sa of a along
        axis_a (body a's frame): (R_a e) . (p_b - p_a) = f(t), e =
        axis_a/|axis_a| (1 row; with a prismatic joint: an actuator)."""
        self._items.append(("transdriver", [self._body(a, "a"), as_vector(sa, 2, "sa"),
                                            as_vector(axis_a, 2, "axis_a"), self._body(b, "b"),
                                            as_vector(sb, 2, "sb"), self._law(law)]))

    def initial_state(self):
        """(q0, v0) from the bodies' positions, angles and velocities."""
        q = np.concatenate([[*b["position"], b["angle"]] for b in self._bodies])
        v = np.concatenate([[*b["velocity"], b["angular_velocity"]] for b in self._bodies])
        return q, v

    def _build(self, system):
        """Create the planar body and joint sets and the model in ``system``."""
        if not self._bodies:
            raise ValueError("PlanarMultibody: add at least one body")
        p = system.ptr
        system.check(lib.LGNPy_MultibodyInit(p, len(self._bodies), self._group),
                     "LGNPy_MultibodyInit")
        keep = []

        def ptr(a):
            keep.append(a)
            return double_ptr(a)

        for k, b in enumerate(self._bodies):
            system.check(lib.LGNBodies_SetPlanarMass(p.bodies, k, b["mass"], b["inertia"]),
                         "LGNBodies_SetPlanarMass")
        if np.any(self.gravity != 0.0):
            system.check(lib.LGNBodies_SetGravity(p.bodies, ptr(self.gravity)),
                         "LGNBodies_SetGravity")
        for kind, args in self._items:
            if kind == "revolute":
                a, sa, b, sb = args
                system.check(lib.LGNJoints_AddPlanarRevolute(p.joints, a, ptr(sa), b, ptr(sb)),
                             "LGNJoints_AddPlanarRevolute")
            elif kind == "prismatic":
                a, sa, axis_a, b, sb, angle = args
                system.check(lib.LGNJoints_AddPlanarPrismatic(p.joints, a, ptr(sa), ptr(axis_a),
                                                              b, ptr(sb), angle),
                             "LGNJoints_AddPlanarPrismatic")
            elif kind == "spring":
                a, sa, b, sb, k, c, L0 = args
                system.check(lib.LGNBodies_AddPlanarSpringDamper(p.bodies, a, ptr(sa), b,
                                                                 ptr(sb), k, c, L0),
                             "LGNBodies_AddPlanarSpringDamper")
            elif kind == "rotspring":
                a, b, k, c, rest = args
                system.check(lib.LGNBodies_AddPlanarRotationalSpringDamper(p.bodies, a, b, k, c,
                                                                           rest),
                             "LGNBodies_AddPlanarRotationalSpringDamper")
            else:
                self._add_driver(system, kind, args, ptr)
        self._set_applied_force(system)
        return self.initial_state()


_GROUPS = {"SO3": 1, "R3xSO3": 2, "SE3": 3}


class PythonModel:
    """A model given as Python functions, integrated by Lignum (each
    callback is a Python call: see doc/python.md for the cost).

    Parameters
    ----------
    group : str, int or list
        The configuration group: ``"SO3"``, ``"R3xSO3"``, ``"SE3"``, an int
        n for R^n, or a list of these for their product.
    q0, v0 : arrays
        Initial configuration (length nq) and velocity (length nv).
    mass : function (t, q, M)
        Writes the nv x nv mass matrix into ``M`` (zeroed on entry).
    force : function (t, q, v, g)
        Writes g(q, v, t) (the left-hand side: M vdot + g + B^T lambda = 0).
    nconstraints : int
        m, the number of rows of Phi (0: unconstrained).
    constraints : function (t, q, phi), jacobian : function (t, q, B)
        Phi(q, t) (length m) and B (m x nv, zeroed on entry), with m > 0.
    stiffness : function (t, q, v, vdot, lam, K), optional
        Adds d/dq (M vdot + g + B^T lambda) to K (otherwise Lignum uses
        difference quotients).
    damping : function (t, q, v, C), optional
        Adds dg/dv to C.
    curvature : function (t, q, v, z), optional
        z = d/dq (B v) v (index 2 and GGL outputs need it).
    constraint_time : function (t, q, phit), optional
        Phi_t for rheonomic constraints.
    mass_constant : bool
        M does not depend on q (Lignum then factors it once).
    """

    def __init__(self, group, q0, v0, mass, force, nconstraints=0, constraints=None,
                 jacobian=None, stiffness=None, damping=None, curvature=None,
                 constraint_time=None, mass_constant=False):
        factors = group if isinstance(group, (list, tuple)) else [group]
        if not factors:
            raise ValueError("group: empty")
        self._factors = []
        for f in factors:
            if isinstance(f, str):
                if f not in _GROUPS:
                    raise ValueError(f"group: unknown group {f!r} (SO3, R3xSO3, SE3 or an int n)")
                self._factors.append((_GROUPS[f], 0))
            else:
                n = as_int(f, "group")
                if n < 1:
                    raise ValueError(f"group: R^n needs n >= 1, got {n}")
                self._factors.append((0, n))
        self.q0 = np.array(q0, dtype=np.float64)
        self.v0 = np.array(v0, dtype=np.float64)
        self.m = as_int(nconstraints, "nconstraints")
        if self.m < 0:
            raise ValueError("nconstraints: must be >= 0")
        for name, fn, needed in (("mass", mass, True), ("force", force, True),
                                 ("constraints", constraints, self.m > 0),
                                 ("jacobian", jacobian, self.m > 0)):
            if needed and not callable(fn):
                raise TypeError(f"{name}: expected a function")
        for name, fn in (("stiffness", stiffness), ("damping", damping),
                         ("curvature", curvature), ("constraint_time", constraint_time)):
            if fn is not None and not callable(fn):
                raise TypeError(f"{name}: expected a function or None")
        self.functions = dict(mass=mass, force=force, constraints=constraints, jacobian=jacobian,
                              stiffness=stiffness, damping=damping, curvature=curvature,
                              constraint_time=constraint_time)
        self.mass_constant = bool(mass_constant)

    def initial_state(self):
        """(q0, v0) as given."""
        return self.q0, self.v0

    def _build(self, system):
        p, cb, f = system.ptr, system.callbacks, self.functions
        for kind, n in self._factors:
            system.check(lib.LGNPy_AddGroupFactor(p, kind, n), "LGNPy_AddGroupFactor")
        flags = ((lib.LGNPY_HAS_STIFFNESS if f["stiffness"] else 0)
                 | (lib.LGNPY_HAS_DAMPING if f["damping"] else 0)
                 | (lib.LGNPY_HAS_CURVATURE if f["curvature"] else 0)
                 | (lib.LGNPY_HAS_CONSTR_TIME if f["constraint_time"] else 0))
        system.check(lib.LGNPy_PythonModelInit(p, self.m, flags), "LGNPy_PythonModelInit")
        cb.mat[lib.LGNPY_CB_MASS] = f["mass"]
        cb.vec[lib.LGNPY_CB_FORCE] = f["force"]
        cb.vec[lib.LGNPY_CB_CONSTR] = f["constraints"]
        cb.mat[lib.LGNPY_CB_JAC] = f["jacobian"]
        cb.mat[lib.LGNPY_CB_STIFFNESS] = f["stiffness"]
        cb.mat[lib.LGNPY_CB_DAMPING] = f["damping"]
        cb.vec[lib.LGNPY_CB_CURVATURE] = f["curvature"]
        cb.vec[lib.LGNPY_CB_CONSTR_TIME] = f["constraint_time"]
        return self.q0, self.v0
