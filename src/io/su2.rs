//! SU2 native mesh (`.su2`, ASCII, single zone).
//!
//! SU2 has no per-element region in a single-zone file, and it ignores text between sections.
//! So the tets are written grouped by region (stable, so order within a region is kept), and
//! `%` comment lines before `NELEM=` give each region's name and element range. Element lines
//! end with the element index (the legacy form SU2 still accepts and ignores). Markers sharing
//! a name become one `MARKER_TAG`.

use super::names::{clean_name, groups};
use crate::mesh::VolumeMesh;
use std::io::Write;

pub(crate) fn write(w: &mut dyn Write, m: &VolumeMesh) -> std::io::Result<()> {
    writeln!(w, "% tetrafoil volume mesh")?;
    let mut order: Vec<usize> = (0..m.tets.len()).collect();
    order.sort_by_key(|&k| m.tet_region[k]);
    let mut first = 0;
    for (r, region) in m.regions.iter().enumerate() {
        let n = order[first..]
            .iter()
            .take_while(|&&k| m.tet_region[k] as usize == r)
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
    writeln!(w, "NELEM= {}", m.tets.len())?;
    for (i, &k) in order.iter().enumerate() {
        let [a, b, c, d] = m.tets[k];
        writeln!(w, "10 {a} {b} {c} {d} {i}")?;
    }
    writeln!(w, "NPOIN= {}", m.points.len())?;
    for p in &m.points {
        writeln!(w, "{:e} {:e} {:e}", p.x, p.y, p.z)?;
    }
    let g = groups(&m.markers);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); g.names.len()];
    for (t, &marker) in m.boundary_marker.iter().enumerate() {
        members[g.of[marker as usize]].push(t);
    }
    writeln!(w, "NMARK= {}", g.names.len())?;
    for (name, tris) in g.names.iter().zip(&members) {
        writeln!(w, "MARKER_TAG= {name}")?;
        writeln!(w, "MARKER_ELEMS= {}", tris.len())?;
        for &t in tris {
            let [a, b, c] = m.boundary[t];
            writeln!(w, "5 {a} {b} {c}")?;
        }
    }
    Ok(())
}
