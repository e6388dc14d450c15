//! ASCII STL of the boundary: one `solid <name>` block per marker name (the multi-solid form
//! Gmsh and OpenFOAM's snappyHexMesh read as one surface or region per solid). Normals come
//! from each triangle's corner order; a degenerate triangle gets a zero normal.

use super::names::groups;
use crate::mesh::VolumeMesh;
use std::io::Write;

pub(crate) fn write(w: &mut dyn Write, m: &VolumeMesh) -> std::io::Result<()> {
    let g = groups(&m.markers);
    let mut members: Vec<Vec<[u32; 3]>> = vec![Vec::new(); g.names.len()];
    for (f, marker) in m.boundary_faces() {
        // A boundary quad is two triangles.
        let tris = if f.len() == 3 {
            vec![[f[0], f[1], f[2]]]
        } else {
            vec![[f[0], f[1], f[2]], [f[0], f[2], f[3]]]
        };
        members[g.of[marker as usize]].extend(tris);
    }
    for (name, tris) in g.names.iter().zip(&members) {
        writeln!(w, "solid {name}")?;
        for t in tris {
            let [a, b, c] = t.map(|v| m.points[v as usize]);
            let n = (b - a).cross(c - a).normalize_or_zero();
            writeln!(w, "  facet normal {:e} {:e} {:e}", n.x, n.y, n.z)?;
            writeln!(w, "    outer loop")?;
            for p in [a, b, c] {
                writeln!(w, "      vertex {:e} {:e} {:e}", p.x, p.y, p.z)?;
            }
            writeln!(w, "    endloop")?;
            writeln!(w, "  endfacet")?;
        }
        writeln!(w, "endsolid {name}")?;
    }
    Ok(())
}
