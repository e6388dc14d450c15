//! MEDIT / INRIA `.mesh` (ASCII, `MeshVersionFormatted 2` = double precision), the input of
//! mmg, Feflo.a and Medit. References are numbers only: triangles carry marker index + 1 and
//! tets region index + 1 (0 means "no reference" to those tools); `#` comment lines at the
//! top name them. Indices are 1-based. Prisms and pyramids (after `--prisms`) keep the mesh's
//! own node order (bottom triangle counter-clockwise seen from the top; base quad
//! counter-clockwise seen from the apex); boundary quads are `Quadrilaterals`.

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
        writeln!(
            w,
            "# volume element ref {}: {}",
            i + 1,
            one_line(&region.name)
        )?;
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
    section(w, "Quadrilaterals", &m.boundary_quads, &m.quad_marker)?;
    section(w, "Tetrahedra", &m.tets, &m.tet_region)?;
    section(w, "Prisms", &m.prisms, &m.prism_region)?;
    section(w, "Pyramids", &m.pyramids, &m.pyramid_region)?;
    writeln!(w, "\nEnd")
}

/// One keyword's elements, 1-based, each with its reference (index + 1); none when empty.
fn section<const N: usize>(
    w: &mut dyn Write,
    keyword: &str,
    elements: &[[u32; N]],
    refs: &[u32],
) -> std::io::Result<()> {
    if elements.is_empty() {
        return Ok(());
    }
    writeln!(w, "\n{keyword}\n{}", elements.len())?;
    for (e, &r) in elements.iter().zip(refs) {
        for v in e {
            write!(w, "{} ", v + 1)?;
        }
        writeln!(w, "{}", r + 1)?;
    }
    Ok(())
}

/// A comment must stay on its line.
fn one_line(s: &str) -> String {
    s.replace(['\n', '\r'], " ")
}
