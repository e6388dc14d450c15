//! MEDIT / INRIA `.mesh` (ASCII, `MeshVersionFormatted 2` = double precision), the input of
//! mmg, Feflo.a and Medit. References are numbers only: triangles carry marker index + 1 and
//! tets region index + 1 (0 means "no reference" to those tools); `#` comment lines at the
//! top name them. Indices are 1-based.

use crate::mesh::VolumeMesh;
use std::io::Write;

pub(crate) fn write(w: &mut dyn Write, m: &VolumeMesh) -> std::io::Result<()> {
    writeln!(w, "MeshVersionFormatted 2")?;
    writeln!(w)?;
    writeln!(w, "Dimension 3")?;
    writeln!(w)?;
    for (i, marker) in m.markers.iter().enumerate() {
        writeln!(w, "# triangle ref {}: {}", i + 1, one_line(&marker.name))?;
    }
    for (i, region) in m.regions.iter().enumerate() {
        writeln!(w, "# tetrahedron ref {}: {}", i + 1, one_line(&region.name))?;
    }
    writeln!(w, "Vertices\n{}", m.points.len())?;
    for p in &m.points {
        writeln!(w, "{:e} {:e} {:e} 0", p.x, p.y, p.z)?;
    }
    writeln!(w, "\nTriangles\n{}", m.boundary.len())?;
    for (t, &marker) in m.boundary.iter().zip(&m.boundary_marker) {
        let [a, b, c] = t.map(|v| v + 1);
        writeln!(w, "{a} {b} {c} {}", marker + 1)?;
    }
    if !m.tets.is_empty() {
        writeln!(w, "\nTetrahedra\n{}", m.tets.len())?;
        for (t, &region) in m.tets.iter().zip(&m.tet_region) {
            let [a, b, c, d] = t.map(|v| v + 1);
            writeln!(w, "{a} {b} {c} {d} {}", region + 1)?;
        }
    }
    writeln!(w, "\nEnd")
}

/// A comment must stay on its line.
fn one_line(s: &str) -> String {
    s.replace(['\n', '\r'], " ")
}
