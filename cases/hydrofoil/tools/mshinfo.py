#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Summarise Gmsh ASCII .msh files (v2.2 and v4.1): nodes, elements per type, physical groups.

    mshinfo.py FILE.msh [...]          one summary line per file
    mshinfo.py --require volume,clamped,wetted FILE.msh   exit 1 if a group is missing/empty
"""
import sys
from collections import Counter, defaultdict

TYPE_NAMES = {1: "Line2", 2: "Tri3", 3: "Quad4", 4: "Tet4", 5: "Hex8", 6: "Prism6", 8: "Line3",
              9: "Tri6", 10: "Quad9", 11: "Tet10", 12: "Hex27", 15: "Point", 16: "Quad8",
              17: "Hex20", 18: "Prism15"}
TYPE_DIM = {1: 1, 2: 2, 3: 2, 4: 3, 5: 3, 6: 3, 8: 1, 9: 2, 10: 2, 11: 3, 12: 3, 15: 0, 16: 2,
            17: 3, 18: 3}


def sections(path):
    out = {}
    with open(path) as f:
        name, buf = None, []
        for line in f:
            s = line.strip()
            if s.startswith("$End"):
                out[name] = buf
                name, buf = None, []
            elif s.startswith("$") and name is None:
                name = s[1:]
            elif name is not None:
                buf.append(s)
    return out


def summarise(path):
    sec = sections(path)
    version = sec["MeshFormat"][0].split()[0]
    names = {}
    for line in sec.get("PhysicalNames", [])[1:]:
        w = line.split()
        names[(int(w[0]), int(w[1]))] = w[2].strip('"')
    byType = Counter()
    byGroup = defaultdict(Counter)  # group name -> element type counts
    if version.startswith("2"):
        nNodes = int(sec["Nodes"][0])
        for line in sec["Elements"][1:]:
            w = line.split()
            t, ntags = int(w[1]), int(w[2])
            byType[t] += 1
            if ntags > 0:
                g = names.get((TYPE_DIM[t], int(w[3])), w[3])
                byGroup[g][t] += 1
    else:
        ent = sec["Entities"]
        counts = [int(v) for v in ent[0].split()]
        phys = {}
        row = 1
        for dim in range(4):
            for _ in range(counts[dim]):
                w = ent[row].split()
                row += 1
                tag = int(w[0])
                k = 4 if dim == 0 else 7
                nphys = int(w[k])
                phys[(dim, tag)] = [int(v) for v in w[k + 1:k + 1 + nphys]]
        nNodes = int(sec["Nodes"][0].split()[1])
        el = sec["Elements"]
        row = 1
        while row < len(el):
            dim, tag, t, n = (int(v) for v in el[row].split())
            row += 1 + n
            byType[t] += n
            for p in phys.get((dim, tag), []):
                byGroup[names.get((dim, p), str(p))][t] += n
    return version, nNodes, byType, byGroup


def fmt(counter):
    return " ".join(f"{TYPE_NAMES.get(t, t)}:{n}" for t, n in sorted(counter.items()))


def main(argv):
    if argv and argv[0] in ("-h", "--help"):
        print(__doc__.strip())
        return 0
    require = []
    if argv and argv[0] == "--require":
        require = argv[1].split(",")
        argv = argv[2:]
    ok = True
    for path in argv:
        version, nNodes, byType, byGroup = summarise(path)
        groups = "; ".join(f"{g} [{fmt(c)}]" for g, c in sorted(byGroup.items()))
        print(f"{path.split('/')[-1]}: msh {version}, nodes {nNodes}, groups: {groups}")
        for g in require:
            if sum(byGroup.get(g, {}).values()) == 0:
                print(f"error: mshinfo.py: {path}: physical group '{g}' missing or empty",
                      file=sys.stderr)
                ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
