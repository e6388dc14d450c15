//! AFLR3's UGRID (`.ugrid` ASCII, `.lb8.ugrid` little-endian and `.b8.ugrid` big-endian binary:
//! 32-bit integers, 64-bit reals), the input of FUN3D and NASA refine, with a `.mapbc` beside
//! it naming each surface id.
//!
//! The layout (UG_IO's pages): the counts of nodes, boundary triangles, boundary quads, tets,
//! pyramids, prisms and hexes; the coordinates; the triangles, then the quads; a surface id per
//! boundary face; then the cells of each kind, all 1-based. Tets and prisms keep the mesh's
//! order (a tet's first face turns towards its fourth node; a prism's bottom towards its top);
//! a pyramid lists two base corners, its apex, then the other two (`[b, a, e, c, d]` of the
//! mesh's `[a, b, c, d, e]`), as meshio reads it. Boundary faces face out of the domain, one
//! orientation on every closed surface as AFLR3 asks.
//!
//! Surface ids are the marker groups (markers sharing a name), numbered from 1. The `.mapbc`
//! lists `id code name` per group with FUN3D's codes for the kind `bc_guess` gives the group:
//! 5000 (far field), 6661/6662/6663 (symmetry x/y/z), 4000 (viscous wall).

use super::bc_guess::{guess, BoundaryKind};
use super::names::{groups, Groups};
use crate::mesh::VolumeMesh;
use std::io::Write;

/// Which UGRID encoding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

/// A pyramid in UGRID's order.
fn pyramid(c: &[u32; 5]) -> [u32; 5] {
    [c[1], c[0], c[4], c[2], c[3]]
}

pub(crate) fn write(w: &mut dyn Write, m: &VolumeMesh, encoding: Encoding) -> std::io::Result<()> {
    let g = groups(&m.markers);
    let mut out = Out::new(w, encoding);
    let counts = [
        m.points.len(),
        m.boundary.len(),
        m.boundary_quads.len(),
        m.tets.len(),
        m.pyramids.len(),
        m.prisms.len(),
        0,
    ];
    for n in counts {
        out.int(count(n)?)?;
    }
    out.end_line()?;
    for p in &m.points {
        for x in p.to_array() {
            out.real(x)?;
        }
        out.end_line()?;
    }
    let one_based = |v: u32| (v + 1) as i32;
    out.cells(m.boundary.iter().map(|f| f.map(one_based)))?;
    out.cells(m.boundary_quads.iter().map(|f| f.map(one_based)))?;
    let surface_id = |k: u32| (g.of[k as usize] + 1) as i32;
    for &k in m.boundary_marker.iter().chain(&m.quad_marker) {
        out.int(surface_id(k))?;
        out.end_line()?;
    }
    out.cells(m.tets.iter().map(|c| c.map(one_based)))?;
    out.cells(m.pyramids.iter().map(|c| pyramid(c).map(one_based)))?;
    out.cells(m.prisms.iter().map(|c| c.map(one_based)))?;
    out.w.flush()
}

fn count(n: usize) -> std::io::Result<i32> {
    i32::try_from(n).map_err(|_| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("UGRID holds 32-bit counts; {n} is too many"),
        )
    })
}

/// The `.mapbc` text: the number of surface ids, then `id code name` per marker group.
pub(crate) fn write_mapbc(w: &mut dyn Write, m: &VolumeMesh) -> std::io::Result<()> {
    let g = groups(&m.markers);
    writeln!(w, "{}", g.names.len())?;
    for (k, name) in g.names.iter().enumerate() {
        writeln!(w, "{} {} {name}", k + 1, fun3d_code(m, &g, k))?;
    }
    Ok(())
}

/// FUN3D's boundary condition code for marker group `k`, from the guessed kind.
fn fun3d_code(m: &VolumeMesh, g: &Groups, k: usize) -> u32 {
    match guess(m, g, k) {
        BoundaryKind::FarField => 5000,
        BoundaryKind::Symmetry(axis) => 6661 + axis as u32,
        // `guess` alone never says Interior: a wake in a UGRID file is listed as a wall
        // (FUN3D takes boundary faces only).
        BoundaryKind::Wall | BoundaryKind::Interior => 4000,
    }
}

/// Numbers in one of the encodings: ASCII separated by spaces, a line per record; binary
/// 32-bit integers and 64-bit reals of the given byte order, no record marks.
struct Out<'a> {
    w: std::io::BufWriter<&'a mut dyn Write>,
    encoding: Encoding,
    first_on_line: bool,
}

impl<'a> Out<'a> {
    fn new(w: &'a mut dyn Write, encoding: Encoding) -> Self {
        Out {
            w: std::io::BufWriter::with_capacity(1 << 20, w),
            encoding,
            first_on_line: true,
        }
    }

    fn gap(&mut self) -> std::io::Result<()> {
        if !self.first_on_line {
            self.w.write_all(b" ")?;
        }
        self.first_on_line = false;
        Ok(())
    }

    fn int(&mut self, v: i32) -> std::io::Result<()> {
        match self.encoding {
            Encoding::Ascii => {
                self.gap()?;
                write!(self.w, "{v}")
            }
            Encoding::LittleEndian => self.w.write_all(&v.to_le_bytes()),
            Encoding::BigEndian => self.w.write_all(&v.to_be_bytes()),
        }
    }

    fn real(&mut self, v: f64) -> std::io::Result<()> {
        match self.encoding {
            Encoding::Ascii => {
                self.gap()?;
                // Shortest text that reads back to the same bits.
                write!(self.w, "{v:e}")
            }
            Encoding::LittleEndian => self.w.write_all(&v.to_le_bytes()),
            Encoding::BigEndian => self.w.write_all(&v.to_be_bytes()),
        }
    }

    fn end_line(&mut self) -> std::io::Result<()> {
        if self.encoding == Encoding::Ascii {
            self.w.write_all(b"\n")?;
        }
        self.first_on_line = true;
        Ok(())
    }

    fn cells<const N: usize>(
        &mut self,
        cells: impl Iterator<Item = [i32; N]>,
    ) -> std::io::Result<()> {
        for c in cells {
            for v in c {
                self.int(v)?;
            }
            self.end_line()?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Marker;
    use glam::DVec3;

    #[test]
    fn mapbc_codes_follow_the_names_and_the_planes() {
        let marker = |id, name: &str| Marker {
            id,
            name: name.into(),
        };
        let m = VolumeMesh {
            points: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.0, 0.0, 1.0),
                DVec3::new(0.0, 1.0, 0.0),
            ],
            boundary: vec![[0, 1, 2], [0, 1, 3], [1, 2, 3], [0, 2, 3]],
            boundary_marker: vec![0, 1, 2, 3],
            markers: vec![
                marker(0, "symmetry"),
                marker(1, "sym_tilted_but_z0"),
                marker(2, "farfield"),
                marker(3, "wing"),
            ],
            ..Default::default()
        };
        let mut text = Vec::new();
        write_mapbc(&mut text, &m).unwrap();
        // y = 0 plane: 6662; z = 0 plane: 6663; far field 5000; a wall 4000.
        assert_eq!(
            String::from_utf8(text).unwrap(),
            "4\n1 6662 symmetry\n2 6663 sym_tilted_but_z0\n3 5000 farfield\n4 4000 wing\n"
        );
    }

    #[test]
    fn the_ascii_file_lists_counts_coordinates_faces_ids_and_cells() {
        let m = VolumeMesh {
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            tets: vec![[0, 1, 2, 3]],
            tet_region: vec![0],
            boundary: vec![[0, 2, 1]],
            boundary_marker: vec![0],
            markers: vec![Marker {
                id: 0,
                name: "bottom".into(),
            }],
            ..Default::default()
        };
        let mut text = Vec::new();
        write(&mut text, &m, Encoding::Ascii).unwrap();
        assert_eq!(
            String::from_utf8(text).unwrap(),
            "4 1 0 1 0 0 0\n0e0 0e0 0e0\n1e0 0e0 0e0\n0e0 1e0 0e0\n0e0 0e0 1e0\n1 3 2\n1\n1 2 3 4\n"
        );
        let mut bytes = Vec::new();
        write(&mut bytes, &m, Encoding::BigEndian).unwrap();
        // 7 counts, 12 reals, 3 + 1 + 4 integers.
        assert_eq!(bytes.len(), 7 * 4 + 12 * 8 + 8 * 4);
        assert_eq!(&bytes[..4], &4i32.to_be_bytes());
    }
}
