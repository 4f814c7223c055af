#!/usr/bin/env python3
"""Read the files of test_vtk_write back with VTK's own XML reader and check
them against the poses it wrote (DIR/poses.txt, %.17g): the .pvd lists
each .vtp with its time; each .vtp's field data "pose" equals q exactly;
every vertex of every shape, taken back to its body's frame with the pose
(rotation from the quaternion, computed here), lies on its shape (box
corners, cylinder rim and caps, sphere, the mesh's points) to 1e-14; the
frames' axes start and end where they should. Exit 77 (skipped) without
VTK's Python module. Usage: check_vtk.py DIR"""
import sys
import xml.etree.ElementTree as ET

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    import numpy as np
except ImportError as e:
    print("VTK's Python module (python3-vtk9) is missing: skipped (%s)" % e)
    sys.exit(77)

d = sys.argv[1]
fails = 0


def check(cond, what):
    global fails
    if not cond:
        fails += 1
        print("FAIL:", what)


def rot(p):  # unit quaternion (w, x, y, z) -> R (independent of Lignum)
    w, x, y, z = p
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


poses = np.loadtxt(d + "/poses.txt", ndmin=2)
coll = ET.parse(d + "/bodies.pvd").getroot().find("Collection")
sets = coll.findall("DataSet")
check(len(sets) == len(poses), "%d data sets in the .pvd, %d outputs" % (len(sets), len(poses)))
tet = np.array([[0, 0, 0], [0.3, 0, 0], [0, 0.2, 0], [0, 0, 0.1]])
tol = 1e-14
for j, ds in enumerate(sets):
    t = float(ds.get("timestep"))
    check(t == poses[j, 0], "output %d: time %r in the .pvd, %r written" % (j, t, poses[j, 0]))
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(d + "/" + ds.get("file"))
    r.Update()
    pd = r.GetOutput()
    fd = pd.GetFieldData()
    pose = vtk_to_numpy(fd.GetArray("pose")).reshape(-1, 7)
    check(np.array_equal(pose, poses[j, 1:].reshape(4, 7)), "output %d: pose field != q" % j)
    check(vtk_to_numpy(fd.GetArray("time"))[0] == t, "output %d: time field" % j)
    pts = vtk_to_numpy(pd.GetPoints().GetData())
    body = vtk_to_numpy(pd.GetCellData().GetArray("body"))
    axis = vtk_to_numpy(pd.GetCellData().GetArray("axis"))
    ncell = pd.GetNumberOfCells()
    check(ncell == 12 + 4 * 24 + 24 * 22 + 4 + 6, "output %d: %d cells" % (j, ncell))
    worst = 0.0
    seen = set()
    for c in range(ncell):
        ids = pd.GetCell(c).GetPointIds()
        P = np.array([pts[ids.GetId(i)] for i in range(ids.GetNumberOfIds())])
        k = int(body[c])
        if axis[c] >= 0:  # a frame's axis: origin, end
            a = int(axis[c])
            if k == 0:
                x, R = pose[0, :3], rot(pose[0, 3:])
                r0 = np.array([0.1, -0.2, 0.3])
                Rf = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1.0]])
                o, e = x + R @ r0, x + R @ (r0 + 0.1 * Rf[:, a])
            else:
                o = np.array([0.1, -0.2, 0.3])
                e = o + 0.2 * np.eye(3)[:, a]
            worst = max(worst, np.abs(P[0] - o).max(), np.abs(P[1] - e).max())
            seen.add(("frame", k, a))
            continue
        x, R = pose[k, :3], rot(pose[k, 3:])
        Y = (P - x) @ R  # R^T (p - x), row by row
        if k == 0:
            err = np.abs(np.abs(Y) - np.array([0.2, 0.1, 0.05])).max()
        elif k == 1:
            rad = np.hypot(Y[:, 0], Y[:, 1])
            err = max(np.minimum(np.abs(rad - 0.05), rad).max(), np.abs(np.abs(Y[:, 2]) - 0.4).max())
        elif k == 2:
            err = np.abs(np.linalg.norm(Y, axis=1) - 0.15).max()
        else:
            err = max(np.abs(tet - y).max(axis=1).min() for y in Y)
        worst = max(worst, err)
        seen.add(("body", k))
    check(len(seen) == 4 + 6, "output %d: %d bodies and frames drawn, 10 expected" % (j, len(seen)))
    check(worst <= tol, "output %d: a vertex off its shape or frame by %.3g" % (j, worst))
    print("output %d (t = %g): %d cells, poses equal, vertices on their shapes to %.2g"
          % (j, t, ncell, worst))
print("check_vtk: %d failures" % fails)
sys.exit(1 if fails else 0)
