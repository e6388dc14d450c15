#!/usr/bin/env python3
"""Load a .msh file in Gmsh (pip install gmsh) and print what Gmsh sees, as JSON: the file's
format line, node count, element counts by type, tets Gmsh finds inverted (minSICN <= 0),
physical groups with their names and element counts, and Gmsh's warnings and errors. Used to check tetrafoil's MSH 4.1 / 2.2 writers against Gmsh itself.

    python3 scripts/check-msh.py out/wing.msh
"""
import json
import sys

import gmsh


def main(path):
    with open(path) as f:
        header = [f.readline().strip() for _ in range(2)]
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.logger.start()
        gmsh.open(path)
        inverted = 0
        tets, _ = gmsh.model.mesh.getElementsByType(4)
        if len(tets):
            inverted = sum(q <= 0 for q in gmsh.model.mesh.getElementQualities(tets, "minSICN"))
        node_tags, _, _ = gmsh.model.mesh.getNodes()
        elements = {}
        for etype in gmsh.model.mesh.getElementTypes():
            name = gmsh.model.mesh.getElementProperties(etype)[0]
            tags, _ = gmsh.model.mesh.getElementsByType(etype)
            elements[name] = len(tags)
        groups = []
        for dim, tag in gmsh.model.getPhysicalGroups():
            count = 0
            for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
                _, etags, _ = gmsh.model.mesh.getElements(dim, entity)
                count += sum(len(t) for t in etags)
            groups.append({
                "dim": dim,
                "tag": tag,
                "name": gmsh.model.getPhysicalName(dim, tag),
                "entities": len(gmsh.model.getEntitiesForPhysicalGroup(dim, tag)),
                "elements": count,
            })
        print(json.dumps({
            "file": path,
            "gmsh": gmsh.__version__,
            "format": header[1] if header[0] == "$MeshFormat" else None,
            "nodes": len(node_tags),
            "elements": elements,
            "inverted_tets": int(inverted),
            "physical_groups": groups,
            "messages": [m for m in gmsh.logger.get() if m.startswith(("Warning", "Error"))],
        }, indent=1))
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: check-msh.py FILE.msh")
    main(sys.argv[1])
