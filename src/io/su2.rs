//! SU2 native mesh (`.su2`, ASCII, single zone).
//!
//! SU2 has no per-element region in a single-zone file, and it ignores text between sections.
//! So the tets are written grouped by region (stable, so order within a region is kept), and
//! `%` comment lines before `NELEM=` give each region's name and element range. Element lines
//! end with the element index (the legacy form SU2 still accepts and ignores). Markers sharing
//! a name become one `MARKER_TAG`. Prisms (13) and pyramids (14) follow the tets, in VTK's
//! node order, as SU2 reads them; boundary quads are type 9.

use super::cells::CellNodes;
use super::names::{clean_name, groups};
use crate::mesh::VolumeMesh;
use std::io::Write;

pub(crate) fn write(w: &mut dyn Write, m: &VolumeMesh) -> std::io::Result<()> {
    writeln!(w, "% tetrafoil volume mesh")?;
    let cells: Vec<(u8, super::cells::VtkCell, u32)> = m
        .cells()
        .map(|(kind, c, r)| {
            (
                super::cells::vtk_type(kind),
                super::cells::vtk_order(kind, c),
                r,
            )
        })
        .collect();
    let mut order: Vec<usize> = (0..cells.len()).collect();
    order.sort_by_key(|&k| cells[k].2);
    let mut first = 0;
    for (r, region) in m.regions.iter().enumerate() {
        let n = order[first..]
            .iter()
            .take_while(|&&k| cells[k].2 as usize == r)
            .count();
        if n > 0 {
            writeln!(
                w,
                "% region {r} {}: elements {first} to {}",
                clean_name(&region.name),
                first + n - 1
            )?;
        }
        first += n;
    }
    writeln!(w, "NDIME= 3")?;
    writeln!(w, "NELEM= {}", cells.len())?;
    for (i, &k) in order.iter().enumerate() {
        let (kind, nodes, _) = &cells[k];
        write!(w, "{kind}")?;
        for v in nodes.nodes() {
            write!(w, " {v}")?;
        }
        writeln!(w, " {i}")?;
    }
    writeln!(w, "NPOIN= {}", m.points.len())?;
    for p in &m.points {
        writeln!(w, "{:e} {:e} {:e}", p.x, p.y, p.z)?;
    }
    let g = groups(&m.markers);
    let mut members: Vec<Vec<&[u32]>> = vec![Vec::new(); g.names.len()];
    for (face, marker) in m.boundary_faces() {
        members[g.of[marker as usize]].push(face);
    }
    writeln!(w, "NMARK= {}", g.names.len())?;
    for (name, faces) in g.names.iter().zip(&members) {
        writeln!(w, "MARKER_TAG= {name}")?;
        writeln!(w, "MARKER_ELEMS= {}", faces.len())?;
        for f in faces {
            write!(w, "{}", if f.len() == 3 { 5 } else { 9 })?;
            for v in *f {
                write!(w, " {v}")?;
            }
            writeln!(w)?;
        }
    }
    Ok(())
}
