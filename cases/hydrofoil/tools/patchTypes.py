#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Set the types of the patches of a polyMesh/boundary file written by gmshToFoam (which makes
every physical group a generic `patch` with a `physicalType`).

Usage: patchTypes.py constant/polyMesh/boundary NAME:TYPE [NAME:TYPE ...]
Fails (exit 1) if a named patch is missing; drops the physicalType entries.
"""
import re
import sys


def main(argv):
    if argv and argv[0] in ("-h", "--help"):
        print(__doc__.strip())
        return
    if len(argv) < 2:
        sys.exit(__doc__)
    path, pairs = argv[0], [a.split(":", 1) for a in argv[1:]]
    s = open(path).read()
    for name, kind in pairs:
        s, n = re.subn(r"(\n\s*%s\s*\{[^}]*?type\s+)\w+;" % re.escape(name), r"\g<1>%s;" % kind, s)
        if n != 1:
            sys.exit("error: patchTypes.py: patch '%s' not found in %s" % (name, path))
    s = re.sub(r"\n\s*physicalType\s+\w+;", "", s)
    with open(path, "w") as f:
        f.write(s)


if __name__ == "__main__":
    main(sys.argv[1:])
