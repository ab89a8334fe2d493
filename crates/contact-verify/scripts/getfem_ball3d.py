#!/usr/bin/python3
"""Hertz's ball on a flat (proto/examples/solid_ball_on_flat.json) solved by GetFEM on our own mesh.

Needs GetFEM's Python interface from Debian (`apt-get install python3-getfem`, 5.4.2 in bookworm), run with the
system Python (/usr/bin/python3): the module is not on PyPI. Not run by CI, imported by no test.

Input: a reply of `contact solve` to the example with `"outputs": ["mesh", "displacement"]` (any h_min, T4 or T10).
The script writes the reply's tetrahedra as Gmsh MSH 2.2 ASCII (GetFEM imports it; the reply lists T10 nodes in
Gmsh's order), reads it back with GetFEM and solves the same problem:

- linear isotropic elasticity, E = 210 GPa, nu = 0.3, P1 (T4) or P2 isoparametric (T10) displacements;
- the quarter's symmetry planes x = 0 and y = 0 on rollers (normal component zero, by multipliers);
- the top z = 10 pressed by 15.3846 MPa (P/4 on the quarter's 100 mm2);
- frictionless contact of the face z = 0 with the rigid flat, the ball's curvature in the gap: the obstacle's
  signed distance is z + (x2 + y2)/2R, as our `initial_gap.paraboloid` adds r2/2R to the plane's gap;
  GetFEM's integral contact brick (Alart-Curnier augmented Lagrangian, generalized Newton) with a P1
  multiplier (the contact stress) on the face, or with --contact nodal its nodal brick (one force per face node,
  as our T4 rows; not meant for T10, whose midside nodes would carry forces).

It prints one JSON line: the sizes, the timings (setup: the mesh read and the model built; solve: assembly and the
Newton iterations), GetFEM's and our contact force, peak pressure, patch area and radius (the least-squares fit of
p2 against r2 over the points in contact, which Hertz's p makes a straight line) and u_z at the top's centre.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 /usr/bin/python3 getfem_ball3d.py reply.json \
        [--contact integral|nodal] [--lsolver mumps|superlu]

GF_NOISY=1 prints GetFEM's Newton residuals; GF_DUMP=out.npz saves the face nodes' radii and pressures.
"""

import argparse
import json
import math
import os
import sys
import time

import numpy as np

E, NU = 210000.0, 0.3  # MPa, the example's steel
R_BALL = 50.0  # mm, the paraboloid gap's radius
PRESSURE = 15.384615384615385  # MPa on the quarter's top: P/4 = 1538.46 N over 100 mm2
LOAD = 4.0 * PRESSURE * 100.0  # N, the whole ball's P (the quarter carries P/4)
E_STAR = E / (1.0 - NU**2)
A_HERTZ = (3.0 * LOAD * R_BALL / (4.0 * E_STAR)) ** (1.0 / 3.0)
P0_HERTZ = 3.0 * LOAD / (2.0 * math.pi * A_HERTZ**2)
SIDE = 10.0  # mm, the cube


def write_msh(path, nodes, elements):
    """Gmsh MSH 2.2 ASCII: element type 4 (T4) or 11 (T10, nodes in Gmsh's order, as the reply lists them)."""
    etype = {4: 4, 10: 11}[len(elements[0])]
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for i, (x, y, z) in enumerate(nodes):
            f.write("%d %.17g %.17g %.17g\n" % (i + 1, x, y, z))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elements))
        for i, el in enumerate(elements):
            # two tags: physical 1, elementary 1 (one volume)
            f.write("%d %d 2 1 1 %s\n" % (i + 1, etype, " ".join(str(n + 1) for n in el)))
        f.write("$EndElements\n")


def fit_radius(r, p):
    """a from the least-squares line p2 = p0^2 (1 - r2/a2) through the points in contact (Hertz: exact)."""
    r, p = np.asarray(r), np.asarray(p)
    slope, icept = np.polyfit(r**2, p**2, 1)
    return math.sqrt(-icept / slope)


def ours(reply):
    """Our answer from the reply: force, peak, area (inner and tributary), fitted radius, the top's u_z."""
    s = reply["solid"]
    pts = [q for q in s["points"] if q["in_contact"]]
    r = [math.hypot(q["at"][0], q["at"][1]) for q in pts]
    top = int(np.argmin(np.linalg.norm(np.asarray(s["nodes"]) - [0.0, 0.0, SIDE], axis=1)))
    patch = s["patches"][0]
    return {
        "force": s["resultant"]["force"][2],
        "peak": max(q["pressure"] for q in pts),
        "area": patch["area"],
        "tributary_area": patch["tributary_area"],
        "a_fit": fit_radius(r, [q["pressure"] for q in pts]),
        "uz_top": s["displacement"][top][2],
        "points_in_contact": len(pts),
        "timings_total_with_outputs": reply["timings"]["total"],
    }


def integral_patch(gf, md, mim_c, mf_l, region):
    """The integral brick's contact force, active area, and nodal radii, pressures and in-contact flags."""
    # the contact stress is lambda_n <= 0 in GetFEM's sign: the pressure is its negative
    force = gf.asm_generic(mim_c, 0, "-lambda_n", region, md)
    # The weak multiplier has no pointwise sign (it rings outside the patch, by up to 5 % of p0 just past the edge
    # on the 35k T10 mesh) and the gap is met weakly, so "in contact" is the brick's own active set:
    # Alart-Curnier's p - r g > 0, with the deformed gap g = obstacle + u_z (the obstacle's normal is z to O(r/R)).
    area = gf.asm_generic(mim_c, 0, "Heaviside(-lambda_n - r*(obstacle + u(3)))", region, md)
    ldofs = mf_l.basic_dof_on_region(region)
    pl = -md.variable("lambda_n")
    xl = mf_l.basic_dof_nodes(ldofs)
    r = np.hypot(xl[0], xl[1])
    gap_l = md.interpolation("obstacle + u(3)", mf_l, region)[ldofs]
    inc = pl - md.variable("r")[0] * gap_l > 0
    return force, area, r, pl, inc


def nodal_patch(gf, md, mim_c, mf_u, mf_l, region):
    """The nodal brick's force, tributary area of the pressed nodes, and their radii, pressures and flags."""
    cdofs = mf_u.basic_dof_on_region(region)[0::3]
    xc = mf_u.basic_dof_nodes(cdofs)
    fn = -md.variable("lambda_n")  # nodal forces, compressive lambda_n <= 0
    # each node's share of the face, the integral of its P1 shape function (P1 on T4: same nodes as u)
    w_all = gf.asm_generic(mim_c, 1, "Test_t", region, None, "t", 1, mf_l, np.zeros(mf_l.nbdof()))
    xl = mf_l.basic_dof_nodes()
    index = {tuple(np.round(xl[:, i], 9)): i for i in mf_l.basic_dof_on_region(region)}
    w = np.array([w_all[index[tuple(np.round(xc[:, k], 9))]] for k in range(len(cdofs))])
    pl = fn / w
    inc = fn > 1e-9 * fn.max()  # the nodal brick's complementarity is exact at the nodes
    return fn.sum(), w[inc].sum(), np.hypot(xc[0], xc[1]), pl, inc


def solve_getfem(msh, degree, lsolver, kind):
    import getfem as gf  # the system Python's module (Debian's python3-getfem)

    t0 = time.perf_counter()
    m = gf.Mesh("import", "gmsh", msh)
    # the box's faces by their outward normals (the box is convex: one face per direction)
    regions = {
        "x_min": (1, [-1, 0, 0]),
        "y_min": (2, [0, -1, 0]),
        "z_min": (3, [0, 0, -1]),
        "z_max": (4, [0, 0, 1]),
    }
    for rnum, v in regions.values():
        m.set_region(rnum, m.outer_faces_with_direction(v, 0.01))
    XMIN, YMIN, CONTACT, TOP = (regions[k][0] for k in ("x_min", "y_min", "z_min", "z_max"))

    mf_u = gf.MeshFem(m, 3)
    mf_u.set_classical_fem(degree)  # on the T10's quadratic map: isoparametric P2
    mf_s = gf.MeshFem(m, 1)
    mf_s.set_classical_fem(degree)  # scalar, for the obstacle's level set
    mf_l = gf.MeshFem(m, 1)
    # the integral brick's contact stress, P1 on the face: stable against P2 displacements (T10), not against P1
    # (T4: its pressure oscillates, measured in the benchmark page; use --contact nodal there)
    mf_l.set_classical_fem(1)
    # the stiffness of straight P2 (P1) tetrahedra is a degree-2 (0) polynomial: exact with these rules
    mim = gf.MeshIm(m, gf.Integ("IM_TETRAHEDRON(%d)" % (2 if degree == 2 else 1)))
    # the contact integrand is piecewise (the active set cuts faces): a richer rule on the faces
    mim_c = gf.MeshIm(m, gf.Integ("IM_TETRAHEDRON(5)"))

    md = gf.Model("real")
    md.add_fem_variable("u", mf_u)
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    md.add_initialized_data("lambda_lame", [lam])
    md.add_initialized_data("mu_lame", [mu])
    md.add_isotropic_linearized_elasticity_brick(mim, "u", "lambda_lame", "mu_lame")
    md.add_initialized_data("traction", [0.0, 0.0, -PRESSURE])
    md.add_source_term_brick(mim_c, "u", "traction", TOP)
    # rollers: u . n = 0 on the symmetry planes
    md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", degree, XMIN)
    md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", degree, YMIN)
    # the obstacle's signed distance: the flat z = 0 seen through the ball's gap r2/2R
    xs = mf_s.basic_dof_nodes()
    md.add_initialized_fem_data("obstacle", mf_s, xs[2] + (xs[0] ** 2 + xs[1] ** 2) / (2 * R_BALL))
    h_min = min(m.convex_radius()) * 2.0
    if kind == "integral":
        md.add_filtered_fem_variable("lambda_n", mf_l, CONTACT)
        # augmentation r (stress/length): E over the finest cell, the scale of the stiffness behind a face
        md.add_initialized_data("r", [E / h_min])
        md.add_integral_contact_with_rigid_obstacle_brick(mim_c, "u", "lambda_n", "obstacle", "r", CONTACT, 1)
    else:
        # one nodal force per node of the face (P1: as our T4 rows), the gap sampled at the node
        cdofs = mf_u.basic_dof_on_region(CONTACT)[0::3]
        md.add_variable("lambda_n", len(cdofs))
        # augmentation r (force/length): E times the finest cell, the stiffness behind a node
        md.add_initialized_data("r", [E * h_min])
        expr = "z + (x*x + y*y)/(2*%r)" % R_BALL
        md.add_nodal_contact_with_rigid_obstacle_brick(mim_c, "u", "lambda_n", "r", CONTACT, expr, 1)
    # nothing holds the body along z but the contact: start Newton with the whole body moved down by Hertz's
    # approach a2/R (0.02 mm), which presses the face into the obstacle for r < sqrt(2) a, so the first
    # tangent already has an active set
    u0 = np.zeros(mf_u.nbdof())
    u0[2::3] = -A_HERTZ**2 / R_BALL
    md.set_variable("u", u0)
    t1 = time.perf_counter()
    noisy = ["noisy"] if os.environ.get("GF_NOISY") else []
    it = md.solve("max_res", 1e-9, "max_iter", 40, "lsolver", lsolver, "lsearch", "simplest", *noisy)
    t2 = time.perf_counter()

    u = md.variable("u")
    gap = md.interpolation("obstacle + u(3)", mf_s, CONTACT)
    xu = mf_u.basic_dof_nodes()
    # a vector fem's dofs go (x, y, z) node by node: the z component of the node at the top's centre
    top = 3 * int(np.argmin(np.linalg.norm(xu[:, 2::3].T - [0.0, 0.0, SIDE], axis=1))) + 2
    if kind == "integral":
        force, area, r, pl, inc = integral_patch(gf, md, mim_c, mf_l, CONTACT)
    else:
        force, area, r, pl, inc = nodal_patch(gf, md, mim_c, mf_u, mf_l, CONTACT)
    if os.environ.get("GF_DUMP"):
        np.savez(os.environ["GF_DUMP"], r=r, p=pl)
    return {
        "dofs": int(mf_u.nbdof()),
        "multiplier_dofs": int(md.nbdof() - mf_u.nbdof()),
        "newton_iterations": int(it[0]) if isinstance(it, (tuple, list, np.ndarray)) else it,
        "setup_s": t1 - t0,
        "solve_s": t2 - t1,
        "contact_brick": kind,
        "force": float(force),
        "peak": float(pl.max()),
        "p_apex": float(pl[int(np.argmin(r))]),
        "area": float(area),
        "a_fit": fit_radius(r[inc], pl[inc]),
        "uz_top": float(u[top]),
        "points_in_contact": int(inc.sum()),
        "r": float(md.variable("r")[0]),
        # the deformed gap at the face's nodes (obstacle's normal is z to O(r/R)): negative is penetration
        "min_gap": float(np.min(gap[mf_s.basic_dof_on_region(CONTACT)])),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("reply")
    ap.add_argument("--lsolver", default="mumps", help="mumps (Debian's build has it) or superlu")
    ap.add_argument(
        "--contact",
        default="integral",
        choices=["integral", "nodal"],
        help="GetFEM's integral brick (P1 multiplier) or its nodal one (sensible on T4 only)",
    )
    ap.add_argument("--msh", default=None, help="where to write the Gmsh file (default: beside the reply)")
    args = ap.parse_args()
    reply = json.load(open(args.reply))
    s = reply["solid"]
    msh = args.msh or os.path.splitext(args.reply)[0] + ".msh"
    write_msh(msh, s["nodes"], s["elements"])
    degree = 2 if len(s["elements"][0]) == 10 else 1
    gfr = solve_getfem(msh, degree, args.lsolver, args.contact)
    out = {
        "hertz": {"a": A_HERTZ, "p0": P0_HERTZ, "quarter_area": math.pi * A_HERTZ**2 / 4},
        "element": "t10" if degree == 2 else "t4",
        "nodes": len(s["nodes"]),
        "tetrahedra": len(s["elements"]),
        "ours": ours(reply),
        "getfem": gfr,
        "lsolver": args.lsolver,
        "omp_threads": os.environ.get("OMP_NUM_THREADS"),
    }
    json.dump(out, sys.stdout)
    print()


if __name__ == "__main__":
    main()
