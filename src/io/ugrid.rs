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
//!
//! UGRID has no interior faces: FUN3D and refine take every listed face for a boundary, so a
//! wake's faces (cells on both sides) would be a wall inside the flow. They are left out, with
//! a warning; a group left with no face gets no surface id.

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

/// The boundary faces UGRID lists (those with cells on one side only) and the surface ids:
/// found once for the mesh file and its `.mapbc` (a pass over every cell).
pub(crate) struct Listed {
    groups: Groups,
    triangles: Vec<usize>,
    quads: Vec<usize>,
    /// Per group, its 1-based surface id, or `None` when none of its faces is listed.
    id: Vec<Option<i32>>,
}

pub(crate) fn listed(m: &VolumeMesh) -> Listed {
    let groups = groups(&m.markers);
    let two_sided = crate::mesh::validity::two_sided_boundary_faces(m);
    let (tris, quads) = two_sided.split_at(m.boundary.len());
    let one_sided =
        |both: &[bool]| -> Vec<usize> { (0..both.len()).filter(|&k| !both[k]).collect() };
    let (triangles, quads) = (one_sided(tris), one_sided(quads));
    let mut has_faces = vec![false; groups.names.len()];
    for &k in &triangles {
        has_faces[groups.of[m.boundary_marker[k] as usize]] = true;
    }
    for &k in &quads {
        has_faces[groups.of[m.quad_marker[k] as usize]] = true;
    }
    let mut next = 0;
    let id = has_faces
        .iter()
        .map(|&has| {
            has.then(|| {
                next += 1;
                next
            })
        })
        .collect();
    Listed {
        groups,
        triangles,
        quads,
        id,
    }
}

pub(crate) fn write(
    w: &mut dyn Write,
    m: &VolumeMesh,
    l: &Listed,
    encoding: Encoding,
) -> std::io::Result<()> {
    let left_out = m.boundary_face_count() - l.triangles.len() - l.quads.len();
    if left_out > 0 {
        let names: Vec<&str> = (l.groups.names.iter().zip(&l.id))
            .filter(|(_, id)| id.is_none())
            .map(|(n, _)| n.as_str())
            .collect();
        log::warn!(
            "UGRID has no interior faces: {left_out} boundary faces with cells on both sides \
             (a wake's) are left out{}",
            if names.is_empty() {
                String::new()
            } else {
                format!(", and with them the groups {}", names.join(", "))
            }
        );
    }
    let mut out = Out::new(w, encoding);
    let counts = [
        m.points.len(),
        l.triangles.len(),
        l.quads.len(),
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
    out.cells(l.triangles.iter().map(|&k| m.boundary[k].map(one_based)))?;
    out.cells(l.quads.iter().map(|&k| m.boundary_quads[k].map(one_based)))?;
    let markers = (l.triangles.iter().map(|&k| m.boundary_marker[k]))
        .chain(l.quads.iter().map(|&k| m.quad_marker[k]));
    for marker in markers {
        let id = l.id[l.groups.of[marker as usize]].expect("a listed face's group has an id");
        out.int(id)?;
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
pub(crate) fn write_mapbc(w: &mut dyn Write, m: &VolumeMesh, l: &Listed) -> std::io::Result<()> {
    let kept: Vec<(usize, i32)> = (l.id.iter().enumerate())
        .filter_map(|(k, id)| Some((k, (*id)?)))
        .collect();
    writeln!(w, "{}", kept.len())?;
    for (k, id) in kept {
        let name = &l.groups.names[k];
        writeln!(w, "{id} {} {name}", fun3d_code(m, &l.groups, k))?;
    }
    Ok(())
}

/// FUN3D's boundary condition code for marker group `k`, from the guessed kind.
fn fun3d_code(m: &VolumeMesh, g: &Groups, k: usize) -> u32 {
    match guess(m, g, k) {
        BoundaryKind::FarField => 5000,
        BoundaryKind::Symmetry(axis) => 6661 + axis as u32,
        // `guess` alone never says Interior; the groups listed have faces on the boundary.
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
        write_mapbc(&mut text, &m, &listed(&m)).unwrap();
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
        write(&mut text, &m, &listed(&m), Encoding::Ascii).unwrap();
        assert_eq!(
            String::from_utf8(text).unwrap(),
            "4 1 0 1 0 0 0\n0e0 0e0 0e0\n1e0 0e0 0e0\n0e0 1e0 0e0\n0e0 0e0 1e0\n1 3 2\n1\n1 2 3 4\n"
        );
        let mut bytes = Vec::new();
        write(&mut bytes, &m, &listed(&m), Encoding::BigEndian).unwrap();
        // 7 counts, 12 reals, 3 + 1 + 4 integers.
        assert_eq!(bytes.len(), 7 * 4 + 12 * 8 + 8 * 4);
        assert_eq!(&bytes[..4], &4i32.to_be_bytes());
    }
}
