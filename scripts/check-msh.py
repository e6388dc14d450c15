#!/usr/bin/env python3
"""Load a .msh file in Gmsh (pip install gmsh) and print what Gmsh sees, as JSON: the file's
format line, node count, element counts by type, tets (and per type, tets, prisms and pyramids)
Gmsh finds inverted (minSICN <= 0),
physical groups with their names and element counts, and Gmsh's warnings and errors. Used to check
tetrafoil's MSH 4.1 / 2.2 and CGNS writers against Gmsh itself (any file Gmsh opens works).

    python3 scripts/check-msh.py out/wing.msh
"""
import json
import sys

import gmsh


def main(path):
    with open(path, "rb") as f:  # MSH is text; a CGNS file is binary
        header = [f.readline().decode("latin-1").strip() for _ in range(2)]
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.logger.start()
        gmsh.open(path)
        inverted_by_type = {}
        for etype in (4, 6, 7):  # tetrahedron, prism, pyramid
            tags, _ = gmsh.model.mesh.getElementsByType(etype)
            if len(tags):
                name = gmsh.model.mesh.getElementProperties(etype)[0]
                qualities = gmsh.model.mesh.getElementQualities(tags, "minSICN")
                inverted_by_type[name] = int(sum(q <= 0 for q in qualities))
        inverted = inverted_by_type.get("Tetrahedron 4", 0)
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
            "inverted": inverted_by_type,
            "physical_groups": groups,
            "messages": [m for m in gmsh.logger.get() if m.startswith(("Warning", "Error"))],
        }, indent=1))
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: check-msh.py FILE.msh")
    main(sys.argv[1])
