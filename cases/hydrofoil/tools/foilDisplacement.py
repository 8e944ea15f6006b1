#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The foil's displacement in a moved fluid case, as an interface CSV (x,y,z,ux,uy,uz).

    foilDisplacement.py CASE OUT.csv [--time 0] [--patch foil]

CASE is a fluid case whose mesh was moved (a coupled run's RUN/fluid-baseline: its moved points
in TIME/polyMesh/points, serial or per processor folder, ASCII or binary). Each foil point is
written once (a point on a processor boundary too) with its reference position
(constant/polyMesh/points) and its displacement (moved - reference). The CSV has the columns of
solid-app's interface CSVs, so that rigid.sh --shape-displacement and foilMotion.py
--from-interface take it: the foil shape the coupled flow was solved in (after the mapping),
to be imposed on the fluid mesh of another preset. Exit 2 with one line on stderr when CASE has
no moved mesh or no such patch.
"""
import argparse
import os
import sys

import numpy as np

from foilMotion import caseParts, meshPoints, readFaces, readPatch, readPoints


def fail(message):
    print("error: foilDisplacement.py: " + message, file=sys.stderr)
    sys.exit(2)


def foilDisplacement(case, time, patch):
    """(reference points, displacements): two (n, 3) arrays over the patch's points, each once."""
    refs, disps = [], []
    for part in caseParts(case):
        mesh = os.path.join(part, "constant", "polyMesh")
        moved = os.path.join(part, time, "polyMesh", "points")
        if not os.path.isfile(moved):
            fail(f"{part} has no moved mesh {time}/polyMesh/points (give a coupled run's fluid "
                 f"case, e.g. RUN/fluid-baseline, and the time it wrote)")
        try:
            start, count = readPatch(os.path.join(mesh, "boundary"), patch)
        except (OSError, RuntimeError, AttributeError) as e:
            fail(f"{mesh}/boundary: no patch '{patch}' ({e})")
        if count == 0:
            continue
        order = meshPoints(readFaces(os.path.join(mesh, "faces"), start, count))
        reference = readPoints(os.path.join(mesh, "points"))
        current = readPoints(moved)
        if len(current) != len(reference):
            fail(f"{moved} has {len(current)} points for the {len(reference)} of {mesh}")
        refs.append(reference[order])
        disps.append((current - reference)[order])
    if not refs:
        fail(f"{case}: the patch '{patch}' has no faces")
    ref, disp = np.concatenate(refs), np.concatenate(disps)
    # a point on a processor boundary appears on each rank that holds it: keep it once
    _, first = np.unique(np.round(ref / 1e-9).astype(np.int64), axis=0, return_index=True)
    first.sort()
    return ref[first], disp[first]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("case")
    p.add_argument("out")
    p.add_argument("--time", default="0", help="the written time of the moved mesh (default 0)")
    p.add_argument("--patch", default="foil")
    a = p.parse_args(argv)
    ref, disp = foilDisplacement(a.case, a.time, a.patch)
    with open(a.out, "w") as f:
        f.write(f"# fluid patch {a.patch} of {os.path.abspath(a.case)} time {a.time}\n")
        f.write("x,y,z,ux,uy,uz\n")
        for r, d in zip(ref, disp):
            f.write("%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n" % (tuple(r) + tuple(d)))
    print(f"foilDisplacement: {len(ref)} points of patch {a.patch}, max |d| "
          f"{np.linalg.norm(disp, axis=1).max():.4e} m -> {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
